#include "app/dataset_probe.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <string>

#include "io/dataset_error.hpp"
#include "io/dataset_reader.hpp"
#include "io/dataset_summary.hpp"

extern char** environ;

namespace grip {

int probe_dataset(const char* file) {
  try {
    // What inspect and resume read: the layout, provenance, every object and gripper record,
    // the candidate table and every committed row (the summary checks their checksums).
    const io::DatasetReader reader(file);
    reader.job_id();
    reader.provenance();
    io::summarize(reader);
  } catch (const std::exception&) {
    return 1;
  }
  return 0;
}

void check_dataset_readable(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::string mode = kProbeDatasetMode;
  std::string program = "grip";
  char* argv[] = {program.data(), mode.data(), const_cast<char*>(name.c_str()), nullptr};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, "/proc/self/exe", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    spdlog::warn("{}: cannot check the file in a separate process ({}); reading it directly", name,
                 std::strerror(spawned));
    return;
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return;
  }
  if (!WIFSIGNALED(status)) return;
  const int signal = WTERMSIG(status);
  const std::string what = ::strsignal(signal);
  // A crash inside HDF5 (a memory error, or an assertion that aborts); any other signal came
  // from outside (Ctrl-C, kill) and says nothing about the file.
  if (signal == SIGSEGV || signal == SIGBUS || signal == SIGABRT || signal == SIGFPE ||
      signal == SIGILL) {
    throw io::DatasetError(name + ": the file is damaged: HDF5 cannot read it (reading it " +
                           "crashed the reader: " + what + "); nothing was changed");
  }
  throw io::DatasetError(name + ": checking the file was stopped (" + what +
                         "); nothing was changed");
}

}  // namespace grip
