#pragma once
// What `grip bench labels` reports: per arm (gripper x object model) the verdicts' agreement
// between the defaults and the reference, the closing forces of the fingers in contact, and per
// category the success rate and failure kinds; as a text table, labels.md, labels.csv (one row
// per candidate) and one JSON line.
#include <filesystem>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "bench/labels/labels_benchmark.hpp"

namespace grip::bench {

// One candidate, run at both settings.
struct LabelsPair {
  const RobustnessTrial* defaults = nullptr;
  const RobustnessTrial* reference = nullptr;  // null if the reference did not run it
};

// The candidates of an arm paired by (category, seed, candidate), in the defaults' order.
std::vector<LabelsPair> pair_trials(const LabelsArmResult& arm);

struct ForceSummary {
  int fingers = 0;  // in contact at the end of closing, over trials whose closing ended
  int within = 0;   // of them, within force_tolerance of grip_force
  double min = 0.0, median = 0.0, max = 0.0;  // N; NaN without fingers
};

// The closing forces of the fingers in contact at the end of closing, over the trials whose
// closing ended (trial::TrialOutcome::closed), against `target` +- `tolerance` (N).
ForceSummary force_summary(const std::vector<const RobustnessTrial*>& trials, double target,
                           double tolerance);

struct LabelsArmTally {
  std::string arm;     // "fin-ray x soft"
  int candidates = 0;  // at the defaults
  int trials = 0;      // paired with the reference's
  int agree = 0;       // same verdict (held or not)
  int same_kind = 0;   // same failure kind
  int success_defaults = 0;
  int success_reference = 0;
  ForceSummary forces;                                            // at the defaults
  std::map<std::string, std::map<std::string, int>> by_category;  // category -> kind -> count
  std::map<std::string, ForceSummary> forces_by_category;         // at the defaults
};

std::vector<LabelsArmTally> labels_tallies(const LabelsResult& result);

void write_labels_table(std::ostream& out, const std::vector<LabelsArmTally>& tallies);
// labels.md (settings, tables) and labels.csv in `out`, created if missing.
void write_labels_files(const std::filesystem::path& out, const LabelsResult& result,
                        const std::vector<LabelsArmTally>& tallies);
void write_labels_json_line(std::ostream& out, const LabelsResult& result,
                            const std::vector<LabelsArmTally>& tallies);

}  // namespace grip::bench
