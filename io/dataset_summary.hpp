#pragma once
// Counts and statistics over a dataset's committed candidates, and the committed rows that no
// longer match their checksums: what `grip inspect` prints after the provenance.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "io/candidate_record.hpp"
#include "io/dataset_reader.hpp"

namespace grip::io {

struct Statistics {
  std::uint64_t count = 0;  // values summarized (finite ones)
  double mean = 0;
  double min = 0;
  double median = 0;  // the mean of the two middle values when count is even
  double max = 0;
};

Statistics statistics(std::vector<double> values);

struct Tally {
  std::string name;
  std::uint64_t candidates = 0;
  std::uint64_t done = 0;
  std::uint64_t success = 0;
};

// A committed row that does not match its checksum, and the commit round that wrote it: the
// journal's "done" line (the first is round 1), 0 where no journal beside the file says.
struct DamagedRow {
  Damage damage;
  std::uint64_t round = 0;
};

struct DatasetSummary {
  std::uint64_t candidates = 0;
  std::uint64_t done = 0;  // done flags set and every row matching its checksums
  std::uint64_t success = 0;
  std::vector<Tally> by_gripper;  // in gripper order
  std::vector<Tally> by_object;   // in object order
  Statistics d1;                  // m, over successful candidates
  Statistics d2;                  // m, over successful candidates
  // Pa, the largest von Mises stress of each successful candidate's soft object (fingers) at
  // the settled grasp, over those whose stress was kept.
  Statistics peak_object_stress;
  Statistics peak_finger_stress;
  Statistics wall_time;                                     // s, over done candidates
  std::array<std::uint64_t, kFailureKindCount> failures{};  // done failures by FailureKind
  std::vector<DamagedRow> damaged;  // by candidate; its candidates are not counted as done
};

DatasetSummary summarize(const DatasetReader& reader);

}  // namespace grip::io
