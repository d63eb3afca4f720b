#include "io/agree.hpp"

#include <exception>
#include <string>

#include "io/dataset_error.hpp"

namespace grip::io {

void agree(MPI_Comm comm, const std::function<void()>& step) {
  int size = 0;
  MPI_Comm_size(comm, &size);
  std::string message;
  try {
    step();
  } catch (const std::exception& e) {
    message = e.what();
    if (message.empty()) message = "unknown error";
  }
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const int mine = message.empty() ? size : rank;
  int first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size) return;
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  message.resize(static_cast<std::size_t>(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, first, comm);
  throw DatasetError(message);
}

}  // namespace grip::io
