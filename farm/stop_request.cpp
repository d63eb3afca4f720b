#include "farm/stop_request.hpp"

#include <unistd.h>
#include <csignal>

namespace grip::farm {
namespace {

volatile std::sig_atomic_t requested = 0;

extern "C" void on_stop_signal(int signal) {
  if (requested) _exit(128 + signal);
  requested = 1;
  constexpr char kMessage[] =
      "\ngrip farm: stopping after the batches in flight (signal again to exit now)\n";
  [[maybe_unused]] const auto written = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
}

}  // namespace

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

bool stop_requested() { return requested != 0; }

}  // namespace grip::farm
