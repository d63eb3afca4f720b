#pragma once
// The checkpoint journal beside a dataset (DATASET.h5.journal): a header naming the job, then
// one line per committed batch listing its candidate ids, each line fsync'd before the batch
// counts as done. Only one process (the writer's rank 0) touches it.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace grip::io {

class Journal {
 public:
  struct Contents {
    std::string job_id;
    std::uint64_t candidate_count = 0;
    std::vector<std::uint64_t> done;    // ids of every complete "done" line, in journal order
    std::vector<std::uint64_t> rounds;  // ids per complete "done" line (commit round), in order
    std::uint64_t valid_bytes = 0;      // length up to the end of the last complete line
  };

  static std::filesystem::path path_for(const std::filesystem::path& dataset);

  // Writes a header-only journal atomically: a temporary file, fsync, rename, fsync of the
  // folder. Throws DatasetError if `path` exists.
  static Journal create(const std::filesystem::path& path, const std::string& job_id,
                        std::uint64_t candidate_count);
  // Parses a journal. A last line cut short by a crash is ignored; any other malformed line
  // is a DatasetError naming the file and line.
  static Contents read(const std::filesystem::path& path);
  // Opens a journal read by read() for appending, first cutting it to `valid_bytes`.
  static Journal reopen(const std::filesystem::path& path, std::uint64_t valid_bytes);

  Journal(Journal&& other) noexcept;
  Journal& operator=(Journal&& other) noexcept;
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;
  ~Journal();

  // Appends one line "done <count> <id>..." and fsyncs it.
  void append(std::span<const std::uint64_t> ids);

 private:
  Journal(std::filesystem::path path, int fd) : path_(std::move(path)), fd_(fd) {}

  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace grip::io
