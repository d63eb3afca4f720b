#include "io/resume_state.hpp"

#include <string>

#include "io/dataset_error.hpp"
#include "io/dataset_layout.hpp"
#include "io/hdf5.hpp"
#include "io/journal.hpp"

namespace grip::io {

namespace {

// The dataset opened read-only, or a DatasetError saying why it cannot be resumed.
h5::Handle open_read_only(const std::filesystem::path& path) {
  const std::string name = path.string();
  if (!std::filesystem::exists(path)) {
    throw DatasetError(name + ": no such dataset to resume; run without --resume to create it");
  }
  if (H5Fis_hdf5(name.c_str()) <= 0) {
    throw DatasetError(name +
                       ": not an HDF5 file, so not a grip dataset; nothing was "
                       "changed (choose another output file)");
  }
  return h5::file_handle(
      H5Fopen(name.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
      name +
          ": the file is damaged or truncated and cannot be resumed; nothing was changed "
          "(remove it and its journal to start again)");
}

// Refuses a dataset that a job other than this one (its id `wanted`, its seed `seed`) made.
void check_job(hid_t file, const std::string& name, const std::string& wanted, std::uint64_t seed) {
  const std::string found = h5::read_string_attribute(file, "job_id");
  if (found != wanted) {
    throw DatasetError(
        name + ": made by another job (job id " + found.substr(0, 12) + ", seed " +
        std::to_string(h5::read_uint_attribute(file, "seed")) +
        "), not by this job file and "
        "seed (job id " +
        wanted.substr(0, 12) + ", seed " + std::to_string(seed) +
        "); nothing was changed. Resume with the job and seed that made it, or write to a "
        "new file");
  }
}

}  // namespace

ResumeState read_resume_state(const std::filesystem::path& path, const Provenance& provenance) {
  const std::filesystem::path journal_path = Journal::path_for(path);
  const std::string name = path.string();
  const h5::Handle file = open_read_only(path);
  DatasetLayout layout;
  try {
    layout = DatasetLayout::read(file);
  } catch (const DatasetError& e) {
    throw DatasetError(name + ": cannot resume: " + e.what() + "; nothing was changed");
  }
  const std::string wanted = job_id(provenance.job_text, provenance.seed);
  check_job(file, name, wanted, provenance.seed);
  const Journal::Contents journal = Journal::read(journal_path);
  if (journal.job_id != wanted || journal.candidate_count != layout.candidate_count) {
    throw DatasetError(journal_path.string() +
                       ": the journal belongs to another dataset "
                       "(job id " +
                       journal.job_id.substr(0, 12) + ", " +
                       std::to_string(journal.candidate_count) +
                       " candidates); nothing was "
                       "changed");
  }
  const h5::Handle flags = h5::dataset_handle(H5Dopen2(file, "/candidates/done", H5P_DEFAULT),
                                              name + ": opening the done flags");
  const std::vector<std::uint8_t> in_file = h5::read_all<std::uint8_t>(flags, H5T_NATIVE_UINT8);
  // Done means both: the flag (set after the rows were flushed) and the journal line
  // (written after the flags were flushed). Anything else is redone.
  std::vector<std::uint8_t> journaled(layout.candidate_count, 0);
  for (const std::uint64_t id : journal.done) journaled[id] = 1;
  ResumeState state;
  state.done.assign(layout.candidate_count, 0);
  for (std::size_t id = 0; id < state.done.size(); ++id) {
    state.done[id] = in_file[id] && journaled[id];
  }
  // A committed row whose bytes no longer match its checksums is redone.
  try {
    state.damaged = find_damage(file, layout, state.done);
  } catch (const DatasetError& e) {
    throw DatasetError(name + ": cannot resume: " + e.what() + "; nothing was changed");
  }
  for (const Damage& damage : state.damaged) state.done[damage.candidate] = 0;
  state.journal_bytes = journal.valid_bytes;
  return state;
}

}  // namespace grip::io
