#pragma once
// The journal's protocol between ranks: rank 0 alone holds the journal; every other rank sends
// it the ids of each work unit it has committed, one MPI message per unit, which rank 0 appends.
#include <mpi.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "io/journal.hpp"

namespace grip::io {

class JournalRelay {
 public:
  explicit JournalRelay(MPI_Comm comm);

  // Rank 0: the journal it appends to, once created or reopened.
  void open(Journal journal);
  // Closes the journal; sends still on their way are kept until the relay is destroyed.
  void close() { journal_.reset(); }

  // A batch committed by every rank together: rank 0 appends all its ids as one line.
  void append_batch(std::span<const std::uint64_t> ids);
  // This rank's committed work unit: rank 0 appends its ids at once, another rank sends them.
  void append_unit(const std::vector<std::uint64_t>& ids);
  // Returns at once. Rank 0: appends the ids other ranks have sent (one fsync'd line). Other
  // ranks: releases the sends rank 0 has received.
  void poll();
  // Collective: returns once every rank's units are in the journal, rank 0 calling
  // `while_waiting` and polling as it waits for the others.
  void end_units(const std::function<void()>& while_waiting);

 private:
  struct Send {
    MPI_Request request = MPI_REQUEST_NULL;
    std::vector<std::uint64_t> ids;  // the message's buffer, kept until the send completes
  };

  void receive(const MPI_Status& status);
  void append();

  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0;
  std::optional<Journal> journal_;          // rank 0 only
  std::vector<std::uint64_t> unjournaled_;  // rank 0: committed ids not yet in the journal
  std::uint64_t units_received_ = 0;        // rank 0: messages from other ranks
  std::vector<Send> sends_;                 // other ranks: ids sent to rank 0, maybe not received
  std::uint64_t units_sent_ = 0;
};

}  // namespace grip::io
