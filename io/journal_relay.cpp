#include "io/journal_relay.hpp"

#include <chrono>
#include <thread>
#include <utility>

namespace grip::io {

namespace {

constexpr int kJournalTag = 2601;  // a work unit's ids, sent to rank 0 for its journal
constexpr int kWaitPoll = 20;      // ms between rank 0's looks while it waits for the others

}  // namespace

JournalRelay::JournalRelay(MPI_Comm comm) : comm_(comm) { MPI_Comm_rank(comm, &rank_); }

void JournalRelay::open(Journal journal) { journal_.emplace(std::move(journal)); }

void JournalRelay::append_batch(std::span<const std::uint64_t> ids) {
  if (rank_ == 0) journal_->append(ids);
}

void JournalRelay::append_unit(const std::vector<std::uint64_t>& ids) {
  if (rank_ == 0) {
    unjournaled_.insert(unjournaled_.end(), ids.begin(), ids.end());
    append();
    return;
  }
  sends_.push_back({MPI_REQUEST_NULL, ids});
  Send& send = sends_.back();
  MPI_Isend(send.ids.data(), static_cast<int>(send.ids.size()), MPI_UINT64_T, 0, kJournalTag, comm_,
            &send.request);
  ++units_sent_;
  poll();
}

void JournalRelay::poll() {
  if (rank_ != 0) {
    std::erase_if(sends_, [](Send& send) {
      int done = 0;
      MPI_Test(&send.request, &done, MPI_STATUS_IGNORE);
      return done != 0;
    });
    return;
  }
  for (;;) {
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, kJournalTag, comm_, &arrived, &status);
    if (!arrived) break;
    receive(status);
    ++units_received_;
  }
  append();
}

void JournalRelay::end_units(const std::function<void()>& while_waiting) {
  std::uint64_t total = 0;
  MPI_Request request;
  MPI_Ireduce(&units_sent_, &total, 1, MPI_UINT64_T, MPI_SUM, 0, comm_, &request);
  if (rank_ != 0) {
    MPI_Wait(&request, MPI_STATUS_IGNORE);
    for (Send& send : sends_) MPI_Wait(&send.request, MPI_STATUS_IGNORE);
    sends_.clear();
    return;
  }
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    poll();
    if (done) break;
    while_waiting();
    std::this_thread::sleep_for(std::chrono::milliseconds(kWaitPoll));
  }
  // Every rank has sent all it will: take the messages still on their way.
  for (; units_received_ < total; ++units_received_) {
    MPI_Status status;
    MPI_Probe(MPI_ANY_SOURCE, kJournalTag, comm_, &status);
    receive(status);
  }
  append();
}

// Receives the work unit `status` announces and adds its ids to the unjournaled ones.
void JournalRelay::receive(const MPI_Status& status) {
  int count = 0;
  MPI_Get_count(&status, MPI_UINT64_T, &count);
  const std::size_t at = unjournaled_.size();
  unjournaled_.resize(at + static_cast<std::size_t>(count));
  MPI_Recv(unjournaled_.data() + at, count, MPI_UINT64_T, status.MPI_SOURCE, kJournalTag, comm_,
           MPI_STATUS_IGNORE);
}

void JournalRelay::append() {
  if (unjournaled_.empty()) return;
  journal_->append(unjournaled_);
  unjournaled_.clear();
}

}  // namespace grip::io
