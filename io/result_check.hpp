#pragma once
// The checks a result passes before the writer writes any of it: its candidate is in the
// dataset, pending and handed over once; its sizes are its gripper's and object's; it has a
// trajectory or stress only where the plan gave it a slot.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "io/candidate_record.hpp"
#include "io/dataset_layout.hpp"

namespace grip::io {

// Throws DatasetError "<name>: <problem>" for the first of `results` that does not fit `layout`
// or whose candidate is `done` already.
void check_results(std::span<const CandidateResult> results, const DatasetLayout& layout,
                   const std::vector<std::uint8_t>& done, const std::string& name);

// Throws DatasetError "<name>: candidate ID was handed to the writer twice in one <commit>"
// for the first id that `sorted_ids` holds twice.
void check_once(const std::vector<std::uint64_t>& sorted_ids, const std::string& name,
                const std::string& commit);

}  // namespace grip::io
