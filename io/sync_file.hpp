#pragma once
// The dataset's file as a plain descriptor beside MPI-IO's own: a rank syncs its independent
// writes through it, so that they are on disk before the journal says they are committed.
#include <filesystem>
#include <string>

namespace grip::io {

class SyncFile {
 public:
  SyncFile() = default;
  // Opens `path` read-only (fdatasync needs no more); DatasetError if it cannot.
  explicit SyncFile(const std::filesystem::path& path);
  SyncFile(SyncFile&& other) noexcept;
  SyncFile& operator=(SyncFile&& other) noexcept;
  SyncFile(const SyncFile&) = delete;
  SyncFile& operator=(const SyncFile&) = delete;
  ~SyncFile();

  // Puts this process's writes to the file on disk (fdatasync); DatasetError
  // "<what>: <reason>" if it fails.
  void sync(const std::string& what) const;

 private:
  int fd_ = -1;
};

}  // namespace grip::io
