#include "io/journal.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>

#include "io/dataset_error.hpp"

namespace grip::io {

namespace {

constexpr const char* kMagic = "grip-journal 1";

[[noreturn]] void system_error(const std::filesystem::path& path, const std::string& what) {
  throw DatasetError(path.string() + ": " + what + ": " + std::strerror(errno));
}

// One writer per dataset: the journal's open file holds an exclusive lock for as long as its
// run lives (the kernel drops it when the process dies, however it dies). A second run, or the
// ranks of a killed mpirun that have not noticed yet, cannot write the same dataset at once.
void lock(int fd, const std::filesystem::path& path) {
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    throw DatasetError(path.string() +
                       ": another grip run is writing this dataset (it holds the journal's "
                       "lock); wait until it has ended, or stop it, then resume");
  }
}

void write_all(int fd, const std::string& text, const std::filesystem::path& path) {
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) system_error(path, "cannot write the journal");
    written += static_cast<std::size_t>(n);
  }
}

void sync_folder(const std::filesystem::path& file) {
  const std::filesystem::path folder =
      file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) system_error(folder, "cannot open the folder to sync the journal's name");
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) system_error(folder, "cannot sync the folder holding the journal");
}

}  // namespace

std::filesystem::path Journal::path_for(const std::filesystem::path& dataset) {
  return dataset.string() + ".journal";
}

Journal Journal::create(const std::filesystem::path& path, const std::string& job_id,
                        std::uint64_t candidate_count) {
  if (std::filesystem::exists(path)) {
    throw DatasetError(path.string() + ": a journal already exists; remove it or resume");
  }
  const std::filesystem::path temporary = path.string() + ".tmp";
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) system_error(temporary, "cannot create the journal");
  std::ostringstream header;
  header << kMagic << "\njob " << job_id << "\ncandidates " << candidate_count << '\n';
  write_all(fd, header.str(), temporary);
  if (::fsync(fd) != 0) system_error(temporary, "cannot sync the journal");
  if (::rename(temporary.c_str(), path.c_str()) != 0) {
    ::close(fd);
    system_error(path, "cannot move the new journal into place");
  }
  sync_folder(path);
  // The descriptor now names `path`; keep appending through it.
  const int append_fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  ::close(fd);
  if (append_fd < 0) system_error(path, "cannot open the journal for appending");
  Journal journal(path, append_fd);
  lock(append_fd, path);
  return journal;
}

Journal::Contents Journal::read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw DatasetError(path.string() +
                       ": the checkpoint journal is missing or unreadable, so the dataset beside "
                       "it was never completely created; remove both and start again");
  }
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Contents contents;
  std::size_t line_start = 0;
  int line_number = 0;
  while (line_start < text.size()) {
    const std::size_t end = text.find('\n', line_start);
    if (end == std::string::npos) break;  // a last line cut short: not committed
    ++line_number;
    const std::string line = text.substr(line_start, end - line_start);
    const auto bad = [&](const std::string& why) {
      throw DatasetError(path.string() + ":" + std::to_string(line_number) + ": " + why +
                         "; the journal is damaged, so resuming is unsafe (remove the dataset "
                         "and its journal and start again)");
    };
    std::istringstream fields(line);
    std::string word;
    fields >> word;
    if (line_number == 1) {
      if (line != kMagic) bad("expected '" + std::string(kMagic) + "', found '" + line + "'");
    } else if (line_number == 2) {
      if (word != "job" || !(fields >> contents.job_id)) bad("expected 'job <id>'");
    } else if (line_number == 3) {
      if (word != "candidates" || !(fields >> contents.candidate_count)) {
        bad("expected 'candidates <count>'");
      }
    } else {
      std::uint64_t count = 0;
      if (word != "done" || !(fields >> count)) bad("expected 'done <count> <id>...'");
      for (std::uint64_t i = 0; i < count; ++i) {
        std::uint64_t id = 0;
        if (!(fields >> id)) bad("the line lists fewer ids than its count");
        if (id >= contents.candidate_count) {
          bad("candidate " + std::to_string(id) + " is outside the " +
              std::to_string(contents.candidate_count) + " candidates");
        }
        contents.done.push_back(id);
      }
      if (fields >> word) bad("the line lists more ids than its count");
      contents.rounds.push_back(count);
    }
    line_start = end + 1;
    contents.valid_bytes = line_start;
  }
  if (line_number < 3) {
    throw DatasetError(path.string() +
                       ": the journal's header is incomplete, so the dataset "
                       "beside it was never completely created; remove both and start again");
  }
  return contents;
}

Journal Journal::reopen(const std::filesystem::path& path, std::uint64_t valid_bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) system_error(path, "cannot open the journal for appending");
  Journal journal(path, fd);
  lock(fd, path);
  if (::ftruncate(fd, static_cast<off_t>(valid_bytes)) != 0 || ::fsync(fd) != 0) {
    system_error(path, "cannot cut the journal's unfinished last line");
  }
  return journal;
}

Journal::Journal(Journal&& other) noexcept
    : path_(std::move(other.path_)), fd_(std::exchange(other.fd_, -1)) {}

Journal& Journal::operator=(Journal&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

Journal::~Journal() {
  if (fd_ >= 0) ::close(fd_);
}

void Journal::append(std::span<const std::uint64_t> ids) {
  std::string line = "done " + std::to_string(ids.size());
  for (const std::uint64_t id : ids) line += ' ' + std::to_string(id);
  line += '\n';
  write_all(fd_, line, path_);
  if (::fdatasync(fd_) != 0) system_error(path_, "cannot sync the journal");
}

}  // namespace grip::io
