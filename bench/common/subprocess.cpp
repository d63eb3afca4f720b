#include "bench/common/subprocess.hpp"

#include <spdlog/spdlog.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace grip::bench {

namespace fs = std::filesystem;

int run_process(const std::vector<std::string>& args, const fs::path& log) {
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen(log.c_str(), "w", stdout);
    std::freopen(log.c_str(), "a", stderr);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    std::_Exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

bool plot(const std::string& script, const std::vector<std::string>& arguments,
          const fs::path& out) {
  const fs::path python = "/usr/bin/python3";
  const fs::path path = fs::path(GRIP_SOURCE_DIR) / script;
  if (!fs::exists(python) || !fs::exists(path)) {
    spdlog::warn("no plot: needs {} and {}", python.string(), path.string());
    return false;
  }
  std::vector<std::string> args{python.string(), path.string()};
  args.insert(args.end(), arguments.begin(), arguments.end());
  const fs::path log = out / "plot.log";
  if (run_process(args, log) != 0) {
    spdlog::warn("no plot: {} failed (install python3-matplotlib); see {}", path.string(),
                 log.string());
    return false;
  }
  fs::remove(log);
  return true;
}

}  // namespace grip::bench
