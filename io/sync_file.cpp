#include "io/sync_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "io/dataset_error.hpp"

namespace grip::io {

SyncFile::SyncFile(const std::filesystem::path& path)
    : fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC)) {
  if (fd_ < 0) {
    throw DatasetError(path.string() +
                       ": cannot open the dataset to sync: " + std::strerror(errno));
  }
}

SyncFile::SyncFile(SyncFile&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

SyncFile& SyncFile::operator=(SyncFile&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

SyncFile::~SyncFile() {
  if (fd_ >= 0) ::close(fd_);
}

void SyncFile::sync(const std::string& what) const {
  if (::fdatasync(fd_) != 0) {
    throw DatasetError(what + ": " + std::strerror(errno));
  }
}

}  // namespace grip::io
