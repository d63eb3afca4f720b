#include "farm/stop_request.hpp"

#include <sys/prctl.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>

namespace grip::farm {
namespace {

volatile std::sig_atomic_t requested = 0;
volatile std::sig_atomic_t at_once = 0;

extern "C" void on_stop_signal(int signal) {
  if (at_once) {
    constexpr char kMessage[] = "\ngrip farm: stopped before any trial ran; nothing was written\n";
    [[maybe_unused]] const auto written = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
    _exit(128 + signal);
  }
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

void stop_at_once(bool yes) { at_once = yes ? 1 : 0; }

void end_with_launcher() {
  const bool under_mpirun = std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr ||
                            std::getenv("PMIX_RANK") != nullptr ||
                            std::getenv("PMI_RANK") != nullptr;
  if (!under_mpirun) return;
  const pid_t launcher = ::getppid();
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != launcher) ::raise(SIGKILL);  // it died before the line above
}

}  // namespace grip::farm
