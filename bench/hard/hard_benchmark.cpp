#include "bench/hard/hard_benchmark.hpp"

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "bench/common/subprocess.hpp"

namespace grip::bench {
namespace fs = std::filesystem;
namespace {

std::string number(double value, int precision) {
  if (std::isinf(value)) return "inf";
  std::ostringstream text;
  text << std::setprecision(precision) << value;
  return text.str();
}

std::string fixed(double value, int decimals) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(decimals) << value;
  return text.str();
}

const char* yes_no(bool ok) { return ok ? "yes" : "NO"; }

// A CSV field: quoted, inner quotes doubled.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

void write_markdown(const fs::path& path, const std::vector<HardCaseResult>& results, int threads,
                    double wall_seconds) {
  std::ofstream md(path);
  md << "# grip bench hard\n\n"
     << "Cases run side by side on " << threads << " thread(s); " << fixed(wall_seconds, 1)
     << " s wall in all (solve s: each case's own time in the solver; a shared, noisy machine, "
        "and cases run side by side, so read times as rough). Invariants checked after every "
        "accepted step: no intersection (exact predicates), no inverted tet (det F > 0).\n\n"
     << "| case | challenge | steps | Newton mean | Newton max | line search | min d / d_hat | "
        "min det F | solve s | no intersection | no inversion | solver | physical check | "
        "verdict |\n"
     << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const HardCaseResult& r : results) {
    md << "| " << r.name << " | " << r.challenge << " | " << r.steps.size() << "/"
       << r.planned_steps << " | " << fixed(r.newton_mean(), 1) << " | " << r.newton_max() << " | "
       << r.line_search_total() << " | " << number(r.min_distance_over_d_hat(), 3) << " | "
       << number(r.min_volume_ratio(), 3) << " | " << fixed(r.solve_seconds, 2) << " | "
       << yes_no(r.intersection_free()) << " | " << yes_no(r.inversion_free()) << " | "
       << solver_outcome(r) << " | " << (r.physical_failure.empty() ? "ok" : r.physical_failure)
       << " | " << (r.passed() ? "pass" : "**FAIL**") << " |\n";
  }
}

void write_csv(const fs::path& path, const std::vector<HardCaseResult>& results) {
  std::ofstream csv(path);
  csv << std::setprecision(9)
      << "case,steps,planned_steps,newton_mean,newton_max,line_search_steps,"
         "min_distance_over_d_hat,min_volume_ratio,solve_seconds,check_seconds,"
         "intersection_free,inversion_free,failure_expected,solver_failure,physical_failure,"
         "passed\n";
  for (const HardCaseResult& r : results) {
    csv << r.name << "," << r.steps.size() << "," << r.planned_steps << "," << r.newton_mean()
        << "," << r.newton_max() << "," << r.line_search_total() << ","
        << number(r.min_distance_over_d_hat(), 9) << "," << r.min_volume_ratio() << ","
        << r.solve_seconds << "," << r.check_seconds << "," << r.intersection_free() << ","
        << r.inversion_free() << "," << r.failure_expected << "," << quoted(r.solver_failure) << ","
        << quoted(r.physical_failure) << "," << r.passed() << "\n";
  }
}

void write_steps_csv(const fs::path& path, const std::vector<HardCaseResult>& results) {
  std::ofstream csv(path);
  csv << std::setprecision(9)
      << "case,step,newton_iterations,line_search_steps,min_distance_over_d_hat,"
         "min_volume_ratio\n";
  for (const HardCaseResult& r : results) {
    for (std::size_t s = 0; s < r.steps.size(); ++s) {
      const HardStep& step = r.steps[s];
      csv << r.name << "," << s + 1 << "," << step.newton_iterations << ","
          << step.line_search_steps << "," << number(step.min_distance / r.d_hat, 9) << ","
          << step.min_volume_ratio << "\n";
    }
  }
}

}  // namespace

std::string solver_outcome(const HardCaseResult& r) {
  if (r.solver_failure.empty()) {
    return r.failure_expected ? "ran every step (expected to fail)" : "ran every step";
  }
  return (r.failure_expected ? "failed as expected: " : "FAILED: ") + r.solver_failure;
}

std::vector<HardCase> select_hard_cases(const std::vector<std::string>& names) {
  std::vector<HardCase> all = hard_cases();
  if (names.empty()) return all;
  std::vector<HardCase> chosen;
  for (const std::string& name : names) {
    bool found = false;
    for (const HardCase& c : all) {
      if (c.name == name) {
        chosen.push_back(c);
        found = true;
      }
    }
    if (!found) {
      std::string known;
      for (const HardCase& c : all) known += (known.empty() ? "" : ", ") + c.name;
      throw std::invalid_argument("no hard case '" + name + "' (cases: " + known + ")");
    }
  }
  return chosen;
}

bool all_passed(const std::vector<HardCaseResult>& results) {
  for (const HardCaseResult& r : results) {
    if (!r.passed()) return false;
  }
  return true;
}

std::vector<HardCaseResult> run_hard_benchmark(const HardBenchmarkOptions& options,
                                               std::ostream& out) {
  const std::vector<HardCase> cases = select_hard_cases(options.cases);
  const int threads =
      options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  const auto start = std::chrono::steady_clock::now();
  const std::vector<HardCaseResult> results = run_hard_cases(cases, threads);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  out << cases.size() << " hard case(s) on " << threads << " thread(s), " << fixed(wall, 1)
      << " s wall\n"
      << std::left << std::setw(24) << "case" << std::right << std::setw(8) << "steps"
      << std::setw(8) << "Newton" << std::setw(6) << "max" << std::setw(8) << "LS" << std::setw(11)
      << "min d/dh" << std::setw(10) << "min detF" << std::setw(9) << "solve s"
      << "  inters.  invert.  verdict\n";
  for (const HardCaseResult& r : results) {
    out << std::left << std::setw(24) << r.name << std::right << std::setw(8)
        << (std::to_string(r.steps.size()) + "/" + std::to_string(r.planned_steps)) << std::setw(8)
        << fixed(r.newton_mean(), 1) << std::setw(6) << r.newton_max() << std::setw(8)
        << r.line_search_total() << std::setw(11) << number(r.min_distance_over_d_hat(), 3)
        << std::setw(10) << number(r.min_volume_ratio(), 3) << std::setw(9)
        << fixed(r.solve_seconds, 2) << std::setw(9) << (r.intersection_free() ? "none" : "FOUND")
        << std::setw(9) << (r.inversion_free() ? "none" : "FOUND") << "  "
        << (r.passed() ? "pass" : "FAIL") << "\n";
    if (!r.solver_failure.empty()) out << "    solver: " << solver_outcome(r) << "\n";
    if (!r.physical_failure.empty()) out << "    physical check: " << r.physical_failure << "\n";
  }
  out << (all_passed(results) ? "all cases pass\n" : "SOME CASES FAIL\n") << std::flush;

  fs::create_directories(options.out);
  write_markdown(options.out / "hard.md", results, threads, wall);
  write_csv(options.out / "hard.csv", results);
  write_steps_csv(options.out / "hard_steps.csv", results);
  plot("bench/hard/plot_hard.py",
       {(options.out / "hard.csv").string(), (options.out / "hard_steps.csv").string(),
        (options.out / "hard.png").string()},
       options.out);
  return results;
}

}  // namespace grip::bench
