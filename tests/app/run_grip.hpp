#pragma once
// Runs the built `grip` executable with arguments and captures its exit code and output.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace grip::testing {

struct GripRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// `arguments` is appended to the command line as is (quote what needs quoting).
inline GripRun run_grip(const std::string& arguments) {
  const auto dir = std::filesystem::temp_directory_path();
  const auto out = dir / ("grip_test_out_" + std::to_string(::getpid()));
  const auto err = dir / ("grip_test_err_" + std::to_string(::getpid()));
  const std::string command =
      std::string(GRIP_EXECUTABLE) + " " + arguments + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(command.c_str());
  GripRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = slurp(out);
  run.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return run;
}

// The same with GRIP_CHECK_ARGS=1: grip only parses and validates its command line.
inline GripRun run_grip_checking_args(const std::string& arguments) {
  ::setenv("GRIP_CHECK_ARGS", "1", 1);
  GripRun run = run_grip(arguments);
  ::unsetenv("GRIP_CHECK_ARGS");
  return run;
}

inline int count_lines(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

}  // namespace grip::testing
