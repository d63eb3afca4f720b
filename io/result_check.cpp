#include "io/result_check.hpp"

#include <algorithm>
#include <type_traits>

#include "io/column.hpp"
#include "io/dataset_columns.hpp"
#include "io/dataset_error.hpp"

namespace grip::io {

namespace {

// A trajectory field named like a candidate table column is "trajectory NAME" in messages.
std::string field_label(const Column& column) {
  const std::string name = column.name;
  if (column.place != Place::kTrajectory) return name;
  const auto columns = dataset_columns();
  const bool shared = std::any_of(columns.begin(), columns.end(), [&](const Column& other) {
    return other.place == Place::kResult && name == other.name;
  });
  return shared ? "trajectory " + name : name;
}

// What is wrong with `result`, or "".
std::string check_result(const CandidateResult& result, const DatasetLayout& layout,
                         const std::vector<std::uint8_t>& done) {
  const CandidateRecord& r = result.record;
  const std::string which = "candidate " + std::to_string(r.id);
  if (r.id >= layout.candidate_count) {
    return which + " is outside the dataset's " + std::to_string(layout.candidate_count) +
           " candidates";
  }
  if (done[r.id] != 0) return which + " is already written; a record is written once";
  const Sizes sizes = Sizes::of_candidate(layout, r.id);
  // The first column of `place` whose values in `record` do not fill its row, or "".
  const auto size_problem = [&](Place place, const auto& record) -> std::string {
    using Record = std::remove_cvref_t<decltype(record)>;
    for (const Column& column : dataset_columns()) {
      if (column.place != place) continue;
      const std::size_t got = column.access_to<Record>().size(record);
      const std::size_t want = record_size(column, sizes);
      if (got != want) {
        return which + ": " + field_label(column) + " has " + std::to_string(got) +
               " values, expected " + std::to_string(want);
      }
    }
    return "";
  };
  std::string problem = size_problem(Place::kResult, result);
  if (!problem.empty()) return problem;
  if (result.trajectory) {
    if (layout.frame_slot[r.id] < 0) return which + " has a trajectory but no frame slot";
    problem = size_problem(Place::kTrajectory, *result.trajectory);
    if (!problem.empty()) return problem;
  }
  if (result.stress) {
    if (layout.stress_slot[r.id] < 0) return which + " has stress but no stress slot";
    problem = size_problem(Place::kStress, result);
    if (!problem.empty()) return problem;
  }
  if (result.finger_stress) {
    if (layout.finger_stress_slot[r.id] < 0) {
      return which + " has finger stress but no finger stress slot";
    }
    problem = size_problem(Place::kFingerStress, result);
    if (!problem.empty()) return problem;
  }
  return "";
}

}  // namespace

void check_results(std::span<const CandidateResult> results, const DatasetLayout& layout,
                   const std::vector<std::uint8_t>& done, const std::string& name) {
  for (const CandidateResult& result : results) {
    const std::string problem = check_result(result, layout, done);
    if (!problem.empty()) throw DatasetError(name + ": " + problem);
  }
}

void check_once(const std::vector<std::uint64_t>& sorted_ids, const std::string& name,
                const std::string& commit) {
  const auto repeated = std::adjacent_find(sorted_ids.begin(), sorted_ids.end());
  if (repeated != sorted_ids.end()) {
    throw DatasetError(name + ": candidate " + std::to_string(*repeated) +
                       " was handed to the writer twice in one " + commit);
  }
}

}  // namespace grip::io
