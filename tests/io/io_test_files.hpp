#pragma once
// File helpers for the io tests: this process's rank, a per-test scratch folder every rank agrees
// on, and whole-file bytes to prove a refused resume changed nothing.
#include <mpi.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace grip::io::testing {

inline int world_rank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

inline std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// A fresh folder named by rank 0 and shared with every rank of `comm`.
inline std::filesystem::path shared_scratch(MPI_Comm comm, const std::string& name) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string path;
  if (rank == 0) {
    path = (std::filesystem::temp_directory_path() /
            ("grip_io_" + name + "_" + std::to_string(::getpid())))
               .string();
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  int length = static_cast<int>(path.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm);
  path.resize(static_cast<std::size_t>(length));
  MPI_Bcast(path.data(), length, MPI_CHAR, 0, comm);
  return path;
}

}  // namespace grip::io::testing
