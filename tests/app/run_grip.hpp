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

// A shell command line (such as `mpirun ... grip ...`), its exit code and output.
inline GripRun run_command(const std::string& command) {
  const auto dir = std::filesystem::temp_directory_path();
  const auto out = dir / ("grip_test_out_" + std::to_string(::getpid()));
  const auto err = dir / ("grip_test_err_" + std::to_string(::getpid()));
  const int status = std::system((command + " >" + out.string() + " 2>" + err.string()).c_str());
  GripRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = slurp(out);
  run.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return run;
}

// `arguments` is appended to the command line as is (quote what needs quoting).
inline GripRun run_grip(const std::string& arguments) {
  return run_command(std::string(GRIP_EXECUTABLE) + " " + arguments);
}

// A path in single quotes for the shell (the tests' paths hold no single quote). Built by
// appending: "'" + string + "'" draws a false -Wrestrict warning from GCC 12.
inline std::string quoted(const std::filesystem::path& path) {
  std::string text = "'";
  text += path.string();
  text += '\'';
  return text;
}

// How often `part` occurs in `text`.
inline int count_of(const std::string& text, const std::string& part) {
  int count = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) {
    ++count;
  }
  return count;
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
