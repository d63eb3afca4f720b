#pragma once
// What a resume finds in a dataset and its journal, read on one rank without changing a byte:
// whether this job may resume the file at all, and which candidates are done.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "io/dataset_damage.hpp"
#include "io/provenance.hpp"

namespace grip::io {

struct ResumeState {
  // Per candidate, 1 when done: its file flag and a journal line say so and its rows match
  // their checksums.
  std::vector<std::uint8_t> done;
  std::vector<Damage> damaged;      // committed rows that no longer match, now pending
  std::uint64_t journal_bytes = 0;  // the journal's length up to its last complete line
};

// Throws DatasetError, naming the file and saying that nothing was changed, when `path` is not a
// dataset this job (`provenance`'s job text and seed) made, or its journal is not that
// dataset's.
ResumeState read_resume_state(const std::filesystem::path& path, const Provenance& provenance);

}  // namespace grip::io
