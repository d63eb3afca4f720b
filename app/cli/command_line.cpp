// The only translation unit that includes CLI11 (app/cli/command_line.hpp says why).
#include "app/cli/command_line.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>

#include "app/cli/logging.hpp"
#include "app/cli/output_paths.hpp"
#include "app/cli/petsc_args.hpp"
#include "app/cli/version.hpp"

namespace grip::cli {

// What the parse decided: the chosen command's work, its checks, where its PETSc options go.
struct ProgramState {
  std::function<int()> run;
  // Commands that are another program's (their name -> the program), run before parsing with
  // the whole command line.
  std::map<std::string, std::string> forwarded;
  std::map<const CLI::App*, std::vector<std::function<void()>>> checks;
  // The PETSc options after a lone `--`, and the commands that take them.
  std::vector<std::string> petsc_given;
  std::map<const CLI::App*, std::vector<std::string>*> petsc_targets;
  bool uses_petsc = false;
};

namespace {

// Range checks that say in words what an option takes (CLI11's PositiveNumber and
// NonNegativeNumber print their bound as a 309-digit number); CLI11 puts the option first.
CLI::Validator whole_number_validator(std::int64_t minimum, std::int64_t maximum) {
  const std::string rule =
      maximum == std::numeric_limits<std::int64_t>::max()
          ? "a whole number >= " + std::to_string(minimum)
          : "a whole number from " + std::to_string(minimum) + " to " + std::to_string(maximum);
  return CLI::Validator(
      [minimum, maximum, rule](std::string& input) {
        // from_chars, not CLI11's cast: a number past 64 bits is refused, not saturated.
        std::int64_t value = 0;
        const char* end = input.data() + input.size();
        const auto [stop, error] = std::from_chars(input.data(), end, value);
        if (error == std::errc() && stop == end && value >= minimum && value <= maximum) {
          return std::string();
        }
        return "must be " + rule + ", not '" + input + "'";
      },
      minimum > 0 ? "POSITIVE" : "NONNEGATIVE");
}

CLI::Validator finite_number(const std::string& rule, const std::string& name,
                             std::function<bool(double)> ok) {
  return CLI::Validator(
      [rule, ok](std::string& input) {
        double value = 0;
        if (CLI::detail::lexical_cast(input, value) && std::isfinite(value) && ok(value)) {
          return std::string();
        }
        return "must be a finite number " + rule + ", not '" + input + "'";
      },
      name);
}

std::string command_names(const CLI::App& app) {
  std::string names;
  for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  return names;
}

// Replaces this process with `program` from this executable's folder, given argv as it came.
[[noreturn]] void run_instead(const std::string& program, char** argv) {
  const std::filesystem::path path = sibling_program(program);
  ::execv(path.c_str(), argv);
  std::fprintf(stderr,
               "grip: this command runs %s, which is not built (%s); build it with "
               "'cmake --build build --target %s' (scripts/build.sh builds every program)\n",
               program.c_str(), path.c_str(), program.c_str());
  std::exit(2);
}

}  // namespace

std::filesystem::path sibling_program(const std::string& name) {
  return std::filesystem::read_symlink("/proc/self/exe").parent_path() / name;
}

Check::Check(std::shared_ptr<const CLI::Validator> validator) : validator_(std::move(validator)) {}

Check Check::count() {
  return Check(std::make_shared<const CLI::Validator>(
      whole_number_validator(0, std::numeric_limits<std::int64_t>::max())));
}
Check Check::positive_count() {
  return Check(std::make_shared<const CLI::Validator>(
      whole_number_validator(1, std::numeric_limits<std::int64_t>::max())));
}
Check Check::whole_number(std::int64_t minimum, std::int64_t maximum) {
  return Check(std::make_shared<const CLI::Validator>(whole_number_validator(minimum, maximum)));
}
Check Check::positive() {
  return Check(std::make_shared<const CLI::Validator>(
      finite_number("> 0", "POSITIVE", [](double x) { return x > 0; })));
}
Check Check::non_negative() {
  return Check(std::make_shared<const CLI::Validator>(
      finite_number(">= 0", "NONNEGATIVE", [](double x) { return x >= 0; })));
}
Check Check::fraction() {
  return Check(std::make_shared<const CLI::Validator>(
      finite_number("from 0 to 1", "[0, 1]", [](double x) { return x >= 0 && x <= 1; })));
}
Check Check::poisson_ratio() {
  return Check(std::make_shared<const CLI::Validator>(
      finite_number("in (-1, 0.5)", "(-1, 0.5)", [](double x) { return x > -1 && x < 0.5; })));
}
Check Check::range(int minimum, int maximum) {
  return Check(std::make_shared<const CLI::Validator>(CLI::Range(minimum, maximum)));
}
Check Check::range(double minimum, double maximum) {
  return Check(std::make_shared<const CLI::Validator>(CLI::Range(minimum, maximum)));
}
Check Check::one_of(std::vector<std::string> names) {
  return Check(std::make_shared<const CLI::Validator>(CLI::IsMember(std::move(names))));
}
Check Check::existing_file() {
  return Check(std::make_shared<const CLI::Validator>(CLI::ExistingFile));
}
Check Check::output_file() {
  return Check(std::make_shared<const CLI::Validator>(
      [](std::string& input) { return output_file_problem(input); }, ""));
}
Check Check::custom(std::function<std::string(const std::string&)> problem, std::string name) {
  return Check(std::make_shared<const CLI::Validator>(
      [problem = std::move(problem)](std::string& input) { return problem(input); },
      std::move(name)));
}
Check Check::output_folder() {
  return Check(std::make_shared<const CLI::Validator>(
      [](std::string& input) { return output_folder_problem(input); }, ""));
}

Option& Option::required() {
  option_->required();
  return *this;
}
Option& Option::show_default() {
  option_->capture_default_str();
  return *this;
}
Option& Option::check(const Check& check) {
  option_->check(*check.validator_);
  return *this;
}
Option& Option::list() {
  option_->delimiter(',');
  return *this;
}
Option& Option::needs(const Option& other) {
  option_->needs(other.option_);
  return *this;
}
Option& Option::excludes(const Option& other) {
  option_->excludes(other.option_);
  return *this;
}

template <class T>
Option Command::option(const std::string& name, T& value, const std::string& help) {
  return Option(app_->add_option(name, value, help));
}
template Option Command::option(const std::string&, std::string&, const std::string&);
template Option Command::option(const std::string&, int&, const std::string&);
template Option Command::option(const std::string&, unsigned&, const std::string&);
template Option Command::option(const std::string&, std::int64_t&, const std::string&);
template Option Command::option(const std::string&, std::uint64_t&, const std::string&);
template Option Command::option(const std::string&, double&, const std::string&);
template Option Command::option(const std::string&, std::optional<std::string>&,
                                const std::string&);
template Option Command::option(const std::string&, std::optional<int>&, const std::string&);
template Option Command::option(const std::string&, std::optional<std::uint64_t>&,
                                const std::string&);
template Option Command::option(const std::string&, std::optional<double>&, const std::string&);
template Option Command::option(const std::string&, std::vector<std::string>&, const std::string&);
template Option Command::option(const std::string&, std::vector<int>&, const std::string&);
template Option Command::option(const std::string&, std::vector<double>&, const std::string&);

Option Command::flag(const std::string& name, bool& value, const std::string& help) {
  return Option(app_->add_flag(name, value, help));
}

Option Command::option_text(const std::string& name, std::function<void(const std::string&)> apply,
                            const std::string& help) {
  return Option(app_->add_option_function<std::string>(name, std::move(apply), help));
}

Command Command::subcommand(const std::string& name, const std::string& help) {
  return Command(app_->add_subcommand(name, help), state_);
}

void Command::require_subcommand() { app_->require_subcommand(1); }

void Command::forward_to(const std::string& program) {
  // run_program() runs it before parsing: the whole command line is the other program's.
  state_->forwarded[app_->get_name()] = program;
}

void Command::on_run(std::function<int()> work) {
  app_->callback([state = state_, app = app_, work = std::move(work)] {
    for (const auto& check : state->checks[app]) {
      try {
        check();
      } catch (const UsageError& e) {
        throw CLI::ValidationError(e.option, e.what());
      }
    }
    if (const auto petsc = state->petsc_targets.find(app); petsc != state->petsc_targets.end()) {
      *petsc->second = state->petsc_given;
      state->uses_petsc = true;
    }
    state->run = work;
  });
}

void Command::on_check(std::function<void()> check) {
  state_->checks[app_].push_back(std::move(check));
}

void Command::takes_petsc_options(std::vector<std::string>& options) {
  state_->petsc_targets[app_] = &options;
}

bool Command::given(const std::string& name) const { return app_->count(name) > 0; }

namespace {

// -v, -q and --log-level, for every command.
struct LogOptions {
  bool verbose = false;
  bool quiet = false;
  std::string level = "info";
  std::string chosen() const { return verbose ? "debug" : quiet ? "warn" : level; }
};

// The command the line names: its first word that is not a global option (or "" if none).
std::string command_word(const std::vector<std::string>& args) {
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string& word = args[i];
    if (word == "--log-level") {
      ++i;
    } else if (word.empty() || word[0] != '-') {
      return word;
    } else if (word != "-v" && word != "--verbose" && word != "-q" && word != "--quiet" &&
               word.rfind("--log-level=", 0) != 0) {
      return "";  // --help, --version or a mistake: the parse says which
    }
  }
  return "";
}

// Parses the command line; the exit code of a parse that ends the program (help, version, a
// usage error), or nothing when a command was chosen.
std::optional<int> parse(CLI::App& app, const std::vector<std::string>& args) {
  std::vector<const char*> argv;
  for (const auto& arg : args) argv.push_back(arg.c_str());
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ExtrasError& e) {
    const std::string name = app.get_name();
    if (app.get_subcommands().empty() && args.size() > 1) {
      std::fprintf(stderr, "%s: '%s' is not a %s command (commands: %s); see '%s --help'\n",
                   name.c_str(), e.what() + std::string(e.what()).rfind(' ') + 1, name.c_str(),
                   command_names(app).c_str(), name.c_str());
    } else {
      std::fprintf(stderr, "%s: %s; see '%s --help'\n", name.c_str(), e.what(), name.c_str());
    }
    return 2;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "%s: %s; see '%s --help'\n", app.get_name().c_str(), e.what(),
                 app.get_name().c_str());
    return 2;
  }
  return std::nullopt;
}

}  // namespace

int run_program(const Program& program, int argc, char** argv) {
  const SplitArguments split = split_petsc_arguments(argc, argv);
  CLI::App app{program.description, program.name};
  app.set_version_flag("--version", version_report(), "Print versions and exit");
  app.fallthrough();
  LogOptions log;
  app.add_flag("-v,--verbose", log.verbose, "Log debug messages");
  app.add_flag("-q,--quiet", log.quiet, "Log warnings and errors only");
  app.add_option("--log-level", log.level,
                 "Log level: trace, debug, info, warn, error, critical, off");
  ProgramState state;
  state.petsc_given = split.petsc;
  Command root(&app, &state);
  program.declare(root);

  if (const auto forwarded = state.forwarded.find(command_word(split.grip));
      forwarded != state.forwarded.end()) {
    run_instead(forwarded->second, argv);
  }
  if (const std::optional<int> exit = parse(app, split.grip)) return *exit;
  try {
    configure_logging(log.chosen());
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "%s: --log-level: %s\n", program.name.c_str(), e.what());
    return 2;
  }
  if (!state.run) {
    std::cerr << app.help();
    return 2;
  }
  if (!split.petsc.empty() && !state.uses_petsc) {
    std::fprintf(stderr, "%s: PETSc options were given after '--', but '%s' uses no PETSc\n",
                 program.name.c_str(), app.get_subcommands().front()->get_name().c_str());
    return 2;
  }
  // GRIP_CHECK_ARGS=1 stops here, after every check of the command line and before any work:
  // how scripts/check-doc-commands.py tests the commands the docs show.
  if (const char* check = std::getenv("GRIP_CHECK_ARGS"); check && std::string(check) == "1") {
    return 0;
  }
  try {
    return state.run();
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}

}  // namespace grip::cli
