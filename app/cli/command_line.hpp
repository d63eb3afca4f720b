#pragma once
// grip's command line as its programs declare it: each command file registers its own options
// beside its arguments through Command, and run_program() parses, checks and runs the chosen
// command. A thin face over CLI11, whose headers (CLI11 2.1, Debian 12: header-only, no
// precompiled mode) cost about 12 s of compiler per translation unit: command_line.cpp is the
// only file that includes them.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
class Validator;
}  // namespace CLI

namespace grip::cli {

// What an option's value must be, checked before any work and said in words when it is not.
class Check {
 public:
  static Check count();           // a whole number >= 0
  static Check positive_count();  // a whole number >= 1
  static Check whole_number(std::int64_t minimum, std::int64_t maximum);
  static Check positive();       // a finite number > 0
  static Check non_negative();   // a finite number >= 0
  static Check fraction();       // a finite number from 0 to 1
  static Check poisson_ratio();  // in (-1, 0.5): stable Neo-Hookean elasticity needs it
  static Check range(int minimum, int maximum);
  static Check range(double minimum, double maximum);
  static Check one_of(std::vector<std::string> names);
  static Check existing_file();
  // A file or a folder the command will write: checked before any work, so that a run does not
  // end on a path it cannot write.
  static Check output_file();
  static Check output_folder();
  // `problem` says what is wrong with a value ("must be ..., not 'x'"), or "" when it is right.
  static Check custom(std::function<std::string(const std::string&)> problem, std::string name);

 private:
  friend class Option;
  explicit Check(std::shared_ptr<const CLI::Validator> validator);
  std::shared_ptr<const CLI::Validator> validator_;
};

// One declared option, to say more about it.
class Option {
 public:
  explicit Option(CLI::Option* option) : option_(option) {}
  Option& required();
  Option& show_default();  // --help shows the value the option starts with
  Option& check(const Check& check);
  Option& list();  // a comma-separated list: --envs 1,2,4
  Option& needs(const Option& other);
  Option& excludes(const Option& other);

 private:
  CLI::Option* option_;
};

// An option given on the command line where its command's checks forbid it.
class UsageError : public std::runtime_error {
 public:
  UsageError(std::string option, const std::string& message)
      : std::runtime_error(message), option(std::move(option)) {}
  std::string option;
};

struct ProgramState;

// A command (or a group of commands: `bench`, `asset`) being declared: its options, its
// subcommands, and the work that runs when the command line chooses it.
class Command {
 public:
  Command(CLI::App* app, ProgramState* state) : app_(app), state_(state) {}

  // `name` is "--name" (an option) or "name" (a positional argument). T: std::string, int,
  // unsigned, std::int64_t, std::uint64_t, double, std::optional of these, std::vector of
  // std::string, int or double.
  template <class T>
  Option option(const std::string& name, T& value, const std::string& help);
  Option flag(const std::string& name, bool& value, const std::string& help);
  // An option whose text `apply` takes (after its checks): a value of more than one type.
  Option option_text(const std::string& name, std::function<void(const std::string&)> apply,
                     const std::string& help);

  Command subcommand(const std::string& name, const std::string& help);
  // A group: exactly one of its subcommands must be chosen.
  void require_subcommand();
  // The command runs another program of grip's build, `program` beside this executable, with
  // the whole command line as given (grip bench runs grip-bench): everything after the
  // command's name is that program's to parse. Only a command of the program's root can.
  void forward_to(const std::string& program);

  // Runs once the command line is parsed and checked, if this command was chosen; returns the
  // process exit code. An exception it throws is logged as an error: exit 1.
  void on_run(std::function<int()> work);
  // Called after parsing, before any work, if this command was chosen: throws UsageError for a
  // combination of options the command refuses (exit 2, like any other usage error).
  void on_check(std::function<void()> check);
  // The command takes the PETSc options after a lone `--` into `options`.
  void takes_petsc_options(std::vector<std::string>& options);

  // During on_check: whether the option was given.
  bool given(const std::string& name) const;

 private:
  CLI::App* app_;
  ProgramState* state_;
};

// One of grip's executables: its name in messages, what --help says of it and its commands.
struct Program {
  std::string name;
  std::string description;
  std::function<void(Command& root)> declare;
};

// Parses argv (global options -v, -q, --log-level, --version; PETSc options after a lone `--`),
// checks it, sets up logging and runs the chosen command: its exit code, 2 for a bad command
// line, 1 when the command throws. GRIP_CHECK_ARGS=1 stops after the checks, before any work
// (exit 0): how the docs' commands are tested (docs/command-line.md).
int run_program(const Program& program, int argc, char** argv);

// Another program of grip's build (grip, grip-bench), beside this executable.
std::filesystem::path sibling_program(const std::string& name);

}  // namespace grip::cli
