#include "io/dataset_summary.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <optional>
#include <utility>

#include "io/dataset_error.hpp"
#include "io/journal.hpp"

namespace grip::io {

Statistics statistics(std::vector<double> values) {
  std::erase_if(values, [](double v) { return !std::isfinite(v); });
  Statistics s;
  s.count = values.size();
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(s.count);
  s.min = values.front();
  s.max = values.back();
  const std::size_t middle = values.size() / 2;
  s.median = values.size() % 2 == 1 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
  return s;
}

namespace {

// Per candidate, the last line (from 1) of the journal beside `dataset` that lists it; 0 where
// none does, or there is no readable journal (the file is summarized all the same).
std::vector<std::uint64_t> commit_rounds(const std::filesystem::path& dataset,
                                         std::uint64_t candidates) {
  std::vector<std::uint64_t> rounds(candidates, 0);
  const std::filesystem::path path = Journal::path_for(dataset);
  if (!std::filesystem::exists(path)) return rounds;
  Journal::Contents journal;
  try {
    journal = Journal::read(path);
  } catch (const DatasetError&) {
    return rounds;
  }
  std::size_t next = 0;
  for (std::size_t round = 0; round < journal.rounds.size(); ++round) {
    for (std::uint64_t i = 0; i < journal.rounds[round]; ++i, ++next) {
      const std::uint64_t id = journal.done[next];
      if (id < candidates) rounds[id] = round + 1;
    }
  }
  return rounds;
}

}  // namespace

DatasetSummary summarize(const DatasetReader& reader) {
  const DatasetLayout& layout = reader.layout();
  DatasetSummary summary;
  summary.candidates = layout.candidate_count;
  for (std::uint32_t g = 0; g < layout.grippers.size(); ++g) {
    summary.by_gripper.push_back({reader.gripper(g).name});
  }
  for (std::uint32_t o = 0; o < layout.objects.size(); ++o) {
    summary.by_object.push_back({reader.object(o).name});
  }
  std::vector<std::uint8_t> done = reader.done();
  const std::vector<std::uint64_t> rounds = commit_rounds(reader.path(), layout.candidate_count);
  for (Damage& damage : reader.damage()) {
    done[damage.candidate] = 0;
    const std::uint64_t round = rounds[damage.candidate];
    summary.damaged.push_back({std::move(damage), round});
  }
  const std::vector<CandidateRecord> records = reader.candidates();
  std::vector<double> d1, d2, wall_time, peak_object_stress, peak_finger_stress;
  const auto add_peak = [](const std::optional<std::vector<float>>& stress,
                           std::vector<double>& peaks) {
    if (stress && !stress->empty())
      peaks.push_back(*std::max_element(stress->begin(), stress->end()));
  };
  for (std::uint64_t id = 0; id < layout.candidate_count; ++id) {
    Tally& gripper = summary.by_gripper[layout.gripper[id]];
    Tally& object = summary.by_object[layout.object[id]];
    ++gripper.candidates;
    ++object.candidates;
    if (!done[id]) continue;
    const CandidateRecord& r = records[id];
    ++summary.done;
    ++gripper.done;
    ++object.done;
    wall_time.push_back(r.wall_time);
    if (r.status == Status::kSuccess) {
      ++summary.success;
      ++gripper.success;
      ++object.success;
      d1.push_back(r.d1);
      d2.push_back(r.d2);
      add_peak(reader.stress(id), peak_object_stress);
      add_peak(reader.finger_stress(id), peak_finger_stress);
    } else if (static_cast<std::uint8_t>(r.failure) < kFailureKindCount) {
      ++summary.failures[static_cast<std::uint8_t>(r.failure)];
    }
  }
  summary.d1 = statistics(std::move(d1));
  summary.d2 = statistics(std::move(d2));
  summary.peak_object_stress = statistics(std::move(peak_object_stress));
  summary.peak_finger_stress = statistics(std::move(peak_finger_stress));
  summary.wall_time = statistics(std::move(wall_time));
  return summary;
}

}  // namespace grip::io
