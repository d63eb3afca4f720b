#include "bench/robustness/robustness_report.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <stdexcept>

#include "bench/common/table_text.hpp"
#include "src/json/json_text.hpp"

namespace grip::bench {
namespace fs = std::filesystem;
namespace {

io::FailureKind kind(std::size_t k) { return static_cast<io::FailureKind>(k); }

// A CSV field: quoted, inner quotes doubled.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// "median / p99 / max" of integers and of iterations per step.
std::string statistics_text(const RankStatistics& s, int decimals) {
  return fixed_or_dash(s.median, decimals) + " / " + fixed_or_dash(s.p99, decimals) + " / " +
         fixed_or_dash(s.max, decimals);
}

// The names of the grippers, in the order they ran.
std::vector<std::string> gripper_order(const RobustnessResult& result) {
  std::vector<std::string> order;
  for (const RobustnessSet& set : result.sets) {
    if (std::find(order.begin(), order.end(), set.gripper) == order.end()) {
      order.push_back(set.gripper);
    }
  }
  return order;
}

nlohmann::ordered_json statistics_json(const RankStatistics& s) {
  return {{"steps", s.count}, {"median", s.median}, {"p99", s.p99}, {"max", s.max}};
}

nlohmann::ordered_json tally_json(const RobustnessTally& t) {
  nlohmann::ordered_json failures = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < t.failures.size(); ++k) {
    failures[std::string(io::to_string(kind(k)))] = t.failures[k];
  }
  return {{"trials", t.trials},
          {"success", t.success},
          {"failure", t.failure},
          {"failures", std::move(failures)},
          {"newton_iterations_per_step", statistics_json(t.iterations_per_step)},
          {"retries", t.retries},
          {"trials_with_retries", t.trials_with_retries}};
}

const RobustnessTally& find_row(const std::vector<RobustnessTally>& rows,
                                const std::string& gripper) {
  for (const RobustnessTally& row : rows) {
    if (row.gripper == gripper && row.objects == "all") return row;
  }
  throw std::logic_error("robustness: no totals for " + gripper);
}

// The shapes and candidates a gripper's sets asked for, in words.
std::string plan_text(const RobustnessResult& result, const std::string& gripper, bool soft) {
  int categories = 0, seeds = 0, candidates = 0;
  for (const RobustnessSet& set : result.sets) {
    if (set.gripper != gripper || set.soft != soft) continue;
    ++categories;
    seeds = set.seeds;
    candidates = set.candidates;
  }
  if (categories == 0) return "none";
  return std::to_string(categories) + " categories x " + std::to_string(seeds) + " shape(s) x " +
         std::to_string(candidates) + " candidates";
}

// Whether the run simulated the production models (every set of a run agrees).
bool production_models(const RobustnessResult& result) {
  return !result.sets.empty() && result.sets.front().production_models;
}

}  // namespace

void write_skipped_and_shortfalls(std::ostream& md, const std::vector<std::string>& skipped,
                                  const std::vector<std::string>& shortfalls) {
  if (!skipped.empty()) {
    md << "\nSeeds skipped (synthesis found no candidate: the shape does not fit the gripper): ";
    for (std::size_t k = 0; k < skipped.size(); ++k) md << (k ? ", " : "") << skipped[k];
    md << ".\n";
  }
  if (!shortfalls.empty()) {
    md << "\nShortfalls (fewer trials than asked):\n\n";
    for (const std::string& s : shortfalls) md << "- " << s << "\n";
  }
}

RankStatistics rank_statistics(const std::vector<long>& counts) {
  RankStatistics s;
  for (const long n : counts) s.count += n;
  if (s.count == 0) {
    s.median = s.p99 = s.max = std::numeric_limits<double>::quiet_NaN();
    return s;
  }
  // The value at rank r (1-based) of the sorted sample.
  const auto at_rank = [&](long r) {
    long seen = 0;
    for (std::size_t n = 0; n < counts.size(); ++n) {
      seen += counts[n];
      if (seen >= r) return static_cast<double>(n);
    }
    return static_cast<double>(counts.size() - 1);
  };
  const auto rank = [&](double q) {
    return std::max(1L, static_cast<long>(std::ceil(q * static_cast<double>(s.count))));
  };
  s.median = at_rank(rank(0.5));
  s.p99 = at_rank(rank(0.99));
  s.max = at_rank(s.count);
  return s;
}

RobustnessTally tally(const std::vector<const RobustnessTrial*>& trials) {
  RobustnessTally t;
  std::vector<long> steps_by_iterations;
  for (const RobustnessTrial* trial : trials) {
    ++t.trials;
    if (trial->status == io::Status::kSuccess) ++t.success;
    if (trial->status == io::Status::kFailure) ++t.failure;
    ++t.failures[static_cast<std::size_t>(trial->failure)];
    t.retries += trial->newton.retries;
    if (trial->newton.retries > 0) ++t.trials_with_retries;
    const std::vector<long>& counts = trial->steps_by_iterations;
    if (steps_by_iterations.size() < counts.size()) steps_by_iterations.resize(counts.size(), 0);
    for (std::size_t n = 0; n < counts.size(); ++n) steps_by_iterations[n] += counts[n];
  }
  t.iterations_per_step = rank_statistics(steps_by_iterations);
  return t;
}

std::vector<RobustnessTally> robustness_rows(const RobustnessResult& result) {
  std::vector<RobustnessTally> rows;
  const auto add = [&](const std::string& gripper, const std::string& objects, auto&& keep) {
    std::vector<const RobustnessTrial*> group;
    for (const RobustnessTrial& trial : result.trials) {
      if ((gripper == "all" || trial.gripper == gripper) && keep(trial)) group.push_back(&trial);
    }
    if (group.empty() && objects != "all") return;
    RobustnessTally t = tally(group);
    t.gripper = gripper;
    t.objects = objects;
    rows.push_back(std::move(t));
  };
  for (const std::string& gripper : gripper_order(result)) {
    std::vector<std::string> categories;
    for (const RobustnessSet& set : result.sets) {
      if (set.gripper == gripper &&
          std::find(categories.begin(), categories.end(), set.category) == categories.end()) {
        categories.push_back(set.category);
      }
    }
    for (const std::string& category : categories) {
      add(gripper, category, [&](const RobustnessTrial& t) { return t.category == category; });
    }
    add(gripper, "rigid", [](const RobustnessTrial& t) { return !t.soft; });
    add(gripper, "soft", [](const RobustnessTrial& t) { return t.soft; });
    add(gripper, "all", [](const RobustnessTrial&) { return true; });
  }
  add("all", "all", [](const RobustnessTrial&) { return true; });
  return rows;
}

void write_robustness_table(std::ostream& out, const std::vector<RobustnessTally>& rows) {
  out << std::left << std::setw(13) << "gripper" << std::setw(10) << "objects" << std::right
      << std::setw(7) << "trials" << std::setw(8) << "success";
  for (std::size_t k = 1; k < io::kFailureKindCount; ++k) {
    out << std::setw(io::to_string(kind(k)).size() + 2) << io::to_string(kind(k));
  }
  out << "  retries  Newton it/step (med/p99/max)\n";
  for (const RobustnessTally& r : rows) {
    out << std::left << std::setw(13) << r.gripper << std::setw(10) << r.objects << std::right
        << std::setw(7) << r.trials << std::setw(8) << r.success;
    for (std::size_t k = 1; k < io::kFailureKindCount; ++k) {
      out << std::setw(io::to_string(kind(k)).size() + 2) << r.failures[k];
    }
    out << std::setw(9) << r.retries << "  " << statistics_text(r.iterations_per_step, 0) << "\n";
  }
  out << std::flush;
}

void write_robustness_files(const fs::path& out, const RobustnessResult& result,
                            const std::vector<RobustnessTally>& rows) {
  fs::create_directories(out);
  std::ofstream md(out / "robustness.md");
  md << "# grip bench robustness\n\n"
     << result.trials.size() << " trials on " << result.threads << " thread(s), "
     << fixed_or_dash(result.wall_seconds, 1)
     << " s wall. Candidates from the synthesizer (`grip synth` defaults, the seed of the "
        "category's shape), trials through the default protocol (`grip trial` defaults), one "
        "solver::Batch per (object, gripper).\n\n"
     << "| gripper | simulated as | rigid objects | soft objects (FEM) |\n"
     << "| --- | --- | --- | --- |\n";
  for (const std::string& gripper : gripper_order(result)) {
    md << "| " << gripper << " | " << robustness_gripper_model(gripper, production_models(result))
       << " | " << plan_text(result, gripper, false) << " | " << plan_text(result, gripper, true)
       << " |\n";
  }
  md << "\nNewton it/step: the Newton iterations of every step the trials took (all parts of a "
        "retried step, and the step a failed trial gave up on); median, 99th percentile and "
        "max by nearest rank. Retries: steps (or parts) rolled back and retried as two half "
        "steps.\n\n"
     << "| gripper | objects | trials | success | failure |";
  for (std::size_t k = 1; k < io::kFailureKindCount; ++k)
    md << " " << io::to_string(kind(k)) << " |";
  md << " retries | Newton it/step (median / p99 / max) |\n|";
  // gripper, objects, trials, success, failure, the kinds but kNone, retries, Newton.
  for (std::size_t c = 0; c < io::kFailureKindCount + 6; ++c) md << " --- |";
  md << "\n";
  for (const RobustnessTally& r : rows) {
    md << "| " << r.gripper << " | " << r.objects << " | " << r.trials << " | " << r.success
       << " | " << r.failure << " |";
    for (std::size_t k = 1; k < io::kFailureKindCount; ++k) md << " " << r.failures[k] << " |";
    md << " " << r.retries << " | " << statistics_text(r.iterations_per_step, 0) << " |\n";
  }
  write_skipped_and_shortfalls(md, result.skipped, result.shortfalls);
  const std::vector<std::string> reasons = [&] {
    std::map<std::string, int> counts;
    for (const RobustnessTrial& t : result.trials) {
      if (t.failure_reason.empty()) continue;
      // "t = 0.06 s: Newton did not converge ...": grouped without the time.
      const std::size_t colon = t.failure_reason.find(": ");
      const bool timed = t.failure_reason.rfind("t = ", 0) == 0 && colon != std::string::npos;
      ++counts[t.gripper + ": " + (timed ? t.failure_reason.substr(colon + 2) : t.failure_reason)];
    }
    std::vector<std::string> lines;
    for (const auto& [reason, n] : counts) lines.push_back(std::to_string(n) + " x " + reason);
    return lines;
  }();
  if (!reasons.empty()) {
    md << "\nThe solver's reasons:\n\n";
    for (const std::string& line : reasons) md << "- " << line << "\n";
  }

  std::ofstream csv(out / "robustness.csv");
  csv << std::setprecision(9)
      << "gripper,category,seed,soft,candidate,status,failure,failure_reason,steps,"
         "newton_iterations,newton_max_iterations,newton_retries\n";
  for (const RobustnessTrial& t : result.trials) {
    csv << t.gripper << "," << t.category << "," << t.seed << "," << (t.soft ? 1 : 0) << ","
        << t.candidate << "," << io::to_string(t.status) << "," << io::to_string(t.failure) << ","
        << quoted(t.failure_reason) << "," << t.newton.steps << "," << t.newton.iterations << ","
        << t.newton.max_iterations << "," << t.newton.retries << "\n";
  }
}

void write_robustness_json_line(std::ostream& out, const RobustnessResult& result,
                                const std::vector<RobustnessTally>& rows) {
  nlohmann::ordered_json grippers = nlohmann::ordered_json::object();
  for (const std::string& gripper : gripper_order(result)) {
    nlohmann::ordered_json g = {
        {"model", robustness_gripper_model(gripper, production_models(result))}};
    g.update(tally_json(find_row(rows, gripper)));
    grippers[gripper] = std::move(g);
  }
  nlohmann::ordered_json line = {{"benchmark", "robustness"},
                                 {"threads", result.threads},
                                 {"wall_seconds", result.wall_seconds}};
  line.update(tally_json(rows.back()));
  line["grippers"] = std::move(grippers);
  line["skipped_seeds"] = result.skipped.size();
  line["shortfalls"] = result.shortfalls.size();
  out << json::text(line, "%.6g") << '\n' << std::flush;
}

}  // namespace grip::bench
