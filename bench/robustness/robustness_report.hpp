#pragma once
// What `grip bench robustness` reports: per gripper and object category, the trials' verdicts,
// failure kinds and Newton iterations, as a text table, robustness.md, robustness.csv (one row
// per trial) and one JSON line of totals.
#include <array>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "bench/robustness/robustness_benchmark.hpp"

namespace grip::bench {

// Nearest-rank statistics of a sample given as a histogram (counts[n]: how many samples are n):
// the median and 99th percentile are the values at ranks ceil(q N) of the sorted sample. All NaN
// for an empty sample.
struct RankStatistics {
  long count = 0;
  double median = 0.0;
  double p99 = 0.0;
  double max = 0.0;
};
RankStatistics rank_statistics(const std::vector<long>& counts);

// Counts and Newton statistics of a group of trials: the Newton iterations of every step the
// group's trials took (the step a failed trial gave up on included), and the retries.
struct RobustnessTally {
  std::string gripper;
  std::string objects;  // a category, or "rigid", "soft", "all" for a gripper's totals
  int trials = 0;
  int success = 0;
  int failure = 0;
  std::array<int, io::kFailureKindCount> failures{};  // by io::FailureKind, kNone included
  RankStatistics iterations_per_step;
  long retries = 0;  // steps (or parts) retried as two half steps, over all trials
  int trials_with_retries = 0;
};

RobustnessTally tally(const std::vector<const RobustnessTrial*>& trials);

// Per gripper (in the order they ran): one row per category, then its rigid, soft and all rows
// (a row only where it has trials). The last row is every trial ("all" x "all").
std::vector<RobustnessTally> robustness_rows(const RobustnessResult& result);

void write_robustness_table(std::ostream& out, const std::vector<RobustnessTally>& rows);

// The seeds whose shape got no candidate and the sets that got fewer trials than asked, as
// Markdown (nothing for empty lists): what a benchmark built on the seed walk did not run.
void write_skipped_and_shortfalls(std::ostream& md, const std::vector<std::string>& skipped,
                                  const std::vector<std::string>& shortfalls);
// robustness.md (settings, table, shortfalls) and robustness.csv (one row per trial) in `out`,
// created if missing.
void write_robustness_files(const std::filesystem::path& out, const RobustnessResult& result,
                            const std::vector<RobustnessTally>& rows);
// One line of JSON (docs/results.md lists its keys).
void write_robustness_json_line(std::ostream& out, const RobustnessResult& result,
                                const std::vector<RobustnessTally>& rows);

}  // namespace grip::bench
