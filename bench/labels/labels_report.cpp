#include "bench/labels/labels_report.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "bench/common/table_text.hpp"
#include "src/json/json_text.hpp"

namespace grip::bench {
namespace fs = std::filesystem;
namespace {

std::string percent(int part, int whole) {
  return whole == 0 ? "-" : fixed_or_dash(100.0 * part / whole, 1) + " %";
}

auto key(const RobustnessTrial& t) { return std::make_tuple(t.category, t.seed, t.candidate); }

}  // namespace

std::vector<LabelsPair> pair_trials(const LabelsArmResult& arm) {
  std::vector<LabelsPair> pairs;
  for (const RobustnessTrial& d : arm.defaults.trials) {
    LabelsPair pair{&d, nullptr};
    for (const RobustnessTrial& r : arm.reference.trials) {
      if (key(r) == key(d)) pair.reference = &r;
    }
    pairs.push_back(pair);
  }
  return pairs;
}

ForceSummary force_summary(const std::vector<const RobustnessTrial*>& trials, double target,
                           double tolerance) {
  std::vector<double> forces;
  ForceSummary s;
  for (const RobustnessTrial* t : trials) {
    if (!t->closed) continue;
    for (const double f : t->closing_forces) {
      if (f <= 0.0) continue;
      forces.push_back(f);
      s.within += std::abs(f - target) <= tolerance;
    }
  }
  s.fingers = static_cast<int>(forces.size());
  if (forces.empty()) {
    s.min = s.median = s.max = std::numeric_limits<double>::quiet_NaN();
    return s;
  }
  std::sort(forces.begin(), forces.end());
  s.min = forces.front();
  s.max = forces.back();
  s.median = forces[(forces.size() - 1) / 2];
  return s;
}

std::vector<LabelsArmTally> labels_tallies(const LabelsResult& result) {
  std::vector<LabelsArmTally> tallies;
  const double target = result.defaults.grip_force;
  const double tolerance = result.defaults.force_tolerance * target;
  for (const LabelsArmResult& arm : result.arms) {
    LabelsArmTally t;
    t.arm = labels_arm_name(arm.arm);
    std::vector<const RobustnessTrial*> defaults;
    std::map<std::string, std::vector<const RobustnessTrial*>> defaults_by_category;
    for (const LabelsPair& pair : pair_trials(arm)) {
      defaults.push_back(pair.defaults);
      ++t.candidates;
      defaults_by_category[pair.defaults->category].push_back(pair.defaults);
      ++t.by_category[pair.defaults->category][verdict_of(*pair.defaults)];
      t.success_defaults += pair.defaults->failure == io::FailureKind::kNone;
      if (!pair.reference) continue;
      ++t.trials;
      t.agree += pair.defaults->status == pair.reference->status;
      t.same_kind += pair.defaults->failure == pair.reference->failure;
      t.success_reference += pair.reference->failure == io::FailureKind::kNone;
    }
    t.forces = force_summary(defaults, target, tolerance);
    for (const auto& [category, trials] : defaults_by_category) {
      t.forces_by_category[category] = force_summary(trials, target, tolerance);
    }
    tallies.push_back(std::move(t));
  }
  return tallies;
}

void write_labels_table(std::ostream& out, const std::vector<LabelsArmTally>& tallies) {
  out << "| arm | candidates | same verdict | same failure kind | held (defaults) | held "
         "(reference) | fingers in contact at the end of closing | within tolerance of the grip "
         "force | "
         "force min / median / max (N) |\n"
         "|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
  for (const LabelsArmTally& t : tallies) {
    // Without a reference the comparison's columns are empty.
    const bool paired = t.trials > 0;
    out << "| " << t.arm << " | " << t.candidates << " | "
        << (paired ? std::to_string(t.agree) + " (" + percent(t.agree, t.trials) + ")" : "-")
        << " | " << (paired ? std::to_string(t.same_kind) : "-") << " | " << t.success_defaults
        << " | " << (paired ? std::to_string(t.success_reference) : "-") << " | "
        << t.forces.fingers << " | " << t.forces.within << " ("
        << percent(t.forces.within, t.forces.fingers) << ") | " << fixed_or_dash(t.forces.min, 1)
        << " / " << fixed_or_dash(t.forces.median, 1) << " / " << fixed_or_dash(t.forces.max, 1)
        << " |\n";
  }
}

namespace {

void write_category_table(std::ostream& out, const std::vector<LabelsArmTally>& tallies) {
  out << "| arm | category | candidates | held | failures | fingers in contact at the end of "
         "closing | within tolerance of the grip force | force min / median / max (N) |\n"
         "|---|---|---:|---:|---|---:|---:|---|\n";
  for (const LabelsArmTally& t : tallies) {
    for (const auto& [category, kinds] : t.by_category) {
      int total = 0;
      std::string failures;
      for (const auto& [kind, n] : kinds) {
        total += n;
        if (kind == "success") continue;
        if (!failures.empty()) failures += ", ";
        failures += std::to_string(n) + " " + kind;
      }
      const auto held = kinds.find("success");
      const int success = held == kinds.end() ? 0 : held->second;
      out << "| " << t.arm << " | " << category << " | " << total << " | " << success << " ("
          << percent(success, total) << ") | " << (failures.empty() ? "-" : failures) << " | ";
      const ForceSummary& f = t.forces_by_category.at(category);
      out << f.fingers << " | " << f.within << " (" << percent(f.within, f.fingers) << ") | "
          << fixed_or_dash(f.min, 1) << " / " << fixed_or_dash(f.median, 1) << " / "
          << fixed_or_dash(f.max, 1) << " |\n";
    }
  }
}

std::string forces_text(const std::vector<double>& forces) {
  std::string text;
  for (const double f : forces) {
    if (!text.empty()) text += ' ';
    text += fixed_or_dash(f, 2);
  }
  return text;
}

}  // namespace

void write_labels_files(const fs::path& out, const LabelsResult& result,
                        const std::vector<LabelsArmTally>& tallies) {
  fs::create_directories(out);
  std::ofstream md(out / "labels.md");
  const trial::TrialParameters& d = result.defaults;
  const trial::TrialParameters& r = result.reference;
  md << "# grip bench labels\n\nDefaults: dt " << d.sim.dt << " s, newton_tol " << d.sim.newton_tol
     << ", " << d.sim.friction_lag_iterations << " friction lag iteration(s), verdict threshold "
     << d.displacement_threshold() * 1e3 << " mm plus eps_v x the time under gravity. ";
  if (!result.refinement.any()) {
    md << "No reference (--refine none)";
  } else {
    md << "Reference: dt " << r.sim.dt << " s, newton_tol " << r.sim.newton_tol << ", "
       << r.sim.friction_lag_iterations << " friction lag iterations, the same threshold ("
       << r.displacement_threshold() * 1e3 << " mm)"
       << (result.refinement.mesh
               ? ", soft objects meshed uniformly inside (the defaults' tets grow with depth)"
               : "")
       << (result.refinement.finger ? ", the fin-ray finger at " + fine_fin_ray_model()
                                    : std::string());
  }
  md << ". Grip force " << d.grip_force << " N, tolerance " << d.force_tolerance * 100 << " %. "
     << result.threads << " thread(s), " << fixed_or_dash(result.wall_seconds / 60, 1)
     << " min.\n\n";
  write_labels_table(md, tallies);
  md << "\nSuccess, failure kinds and closing forces per category, at the defaults:\n\n";
  write_category_table(md, tallies);
  for (const LabelsArmResult& arm : result.arms) {
    for (const std::string& s : arm.defaults.shortfalls) {
      md << "\nShortfall (" << labels_arm_name(arm.arm) << "): " << s << "\n";
    }
  }
  std::ofstream csv(out / "labels.csv");
  csv << "arm,category,seed,candidate,verdict,verdict_reference,closed,closing_forces_n,"
         "settle_displacement_mm,slip_mm,center_displacement_mm,slip_reference_mm,"
         "closing_forces_reference_n,settle_displacement_reference_mm,end_speed_mm_s,"
         "end_speed_reference_mm_s,gravity_s,gravity_reference_s,slip_ratio,slip_ratio_reference\n";
  for (const LabelsArmResult& arm : result.arms) {
    for (const LabelsPair& pair : pair_trials(arm)) {
      const RobustnessTrial& t = *pair.defaults;
      csv << labels_arm_name(arm.arm) << ',' << t.category << ',' << t.seed << ',' << t.candidate
          << ',' << verdict_of(t) << ',' << (pair.reference ? verdict_of(*pair.reference) : "-")
          << ',' << (t.closed ? 1 : 0) << ',' << forces_text(t.closing_forces) << ','
          << fixed_or_dash(t.settle_displacement * 1e3, 4) << ','
          << fixed_or_dash(t.largest_slip * 1e3, 4) << ','
          << fixed_or_dash(t.largest_center_displacement * 1e3, 4) << ','
          << (pair.reference ? fixed_or_dash(pair.reference->largest_slip * 1e3, 4) : "-") << ','
          << (pair.reference ? forces_text(pair.reference->closing_forces) : "-") << ','
          << (pair.reference ? fixed_or_dash(pair.reference->settle_displacement * 1e3, 4) : "-")
          << ',' << fixed_or_dash(t.largest_end_speed * 1e3, 3) << ','
          << (pair.reference ? fixed_or_dash(pair.reference->largest_end_speed * 1e3, 3) : "-")
          << ',' << fixed_or_dash(t.gravity_seconds, 3) << ','
          << (pair.reference ? fixed_or_dash(pair.reference->gravity_seconds, 3) : "-") << ','
          << fixed_or_dash(t.largest_slip_ratio, 4) << ','
          << (pair.reference ? fixed_or_dash(pair.reference->largest_slip_ratio, 4) : "-") << '\n';
    }
  }
}

void write_labels_json_line(std::ostream& out, const LabelsResult& result,
                            const std::vector<LabelsArmTally>& tallies) {
  nlohmann::ordered_json arms = nlohmann::ordered_json::array();
  for (const LabelsArmTally& t : tallies) {
    arms.push_back({{"arm", t.arm},
                    {"candidates", t.candidates},
                    {"paired", t.trials},
                    {"same_verdict", t.agree},
                    {"agreement", t.trials ? static_cast<double>(t.agree) / t.trials : 0.0},
                    {"same_failure_kind", t.same_kind},
                    {"held_defaults", t.success_defaults},
                    {"held_reference", t.success_reference},
                    {"fingers_in_contact", t.forces.fingers},
                    {"fingers_within_tolerance", t.forces.within},
                    {"force_min", t.forces.min},
                    {"force_median", t.forces.median},
                    {"force_max", t.forces.max}});
  }
  const nlohmann::ordered_json root = {{"benchmark", "labels"},
                                       {"threads", result.threads},
                                       {"wall_seconds", result.wall_seconds},
                                       {"arms", std::move(arms)}};
  out << json::text(root, "%.6g") << '\n' << std::flush;
}

}  // namespace grip::bench
