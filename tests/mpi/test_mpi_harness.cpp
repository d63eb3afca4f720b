// Proves the MPI test harness runs real ranks that share one parallel HDF5 file: each of the
// two ranks writes its own row of a dataset collectively, and each reads back the other's row.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <mpi.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <string>

namespace {

int world_rank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

int world_size() {
  int size = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

TEST(MpiHarness, RunsTwoRanksWithDistinctRanks) {
  ASSERT_EQ(world_size(), 2);
  int rank = world_rank();
  int sum = 0;
  MPI_Allreduce(&rank, &sum, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_EQ(sum, 0 + 1);
}

TEST(MpiHarness, RanksWriteOneParallelHdf5FileCollectively) {
  const int rank = world_rank();
  const int size = world_size();
  // Rank 0 picks the path so both ranks open the same file.
  std::array<char, 512> path{};
  if (rank == 0) {
    const auto file = std::filesystem::temp_directory_path() /
                      ("grip_mpi_harness_" + std::to_string(::getpid()) + ".h5");
    file.string().copy(path.data(), path.size() - 1);
  }
  MPI_Bcast(path.data(), static_cast<int>(path.size()), MPI_CHAR, 0, MPI_COMM_WORLD);

  constexpr hsize_t kColumns = 4;
  hid_t access = H5Pcreate(H5P_FILE_ACCESS);
  ASSERT_GE(H5Pset_fapl_mpio(access, MPI_COMM_WORLD, MPI_INFO_NULL), 0);
  hid_t file = H5Fcreate(path.data(), H5F_ACC_TRUNC, H5P_DEFAULT, access);
  ASSERT_GE(file, 0);
  const hsize_t dims[2] = {static_cast<hsize_t>(size), kColumns};
  hid_t space = H5Screate_simple(2, dims, nullptr);
  hid_t dataset =
      H5Dcreate2(file, "rows", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(dataset, 0);

  std::array<double, kColumns> row{};
  for (hsize_t c = 0; c < kColumns; ++c) row[c] = 100.0 * rank + static_cast<double>(c);
  const hsize_t start[2] = {static_cast<hsize_t>(rank), 0};
  const hsize_t count[2] = {1, kColumns};
  H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr);
  hid_t memory = H5Screate_simple(2, count, nullptr);
  hid_t transfer = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(transfer, H5FD_MPIO_COLLECTIVE);
  ASSERT_GE(H5Dwrite(dataset, H5T_NATIVE_DOUBLE, memory, space, transfer, row.data()), 0);
  H5Fflush(file, H5F_SCOPE_GLOBAL);
  MPI_Barrier(MPI_COMM_WORLD);

  // Read the other rank's row back.
  const int other = (rank + 1) % size;
  const hsize_t other_start[2] = {static_cast<hsize_t>(other), 0};
  H5Sselect_hyperslab(space, H5S_SELECT_SET, other_start, nullptr, count, nullptr);
  std::array<double, kColumns> read{};
  ASSERT_GE(H5Dread(dataset, H5T_NATIVE_DOUBLE, memory, space, transfer, read.data()), 0);
  for (hsize_t c = 0; c < kColumns; ++c) {
    EXPECT_EQ(read[c], 100.0 * other + static_cast<double>(c));
  }

  H5Pclose(transfer);
  H5Sclose(memory);
  H5Dclose(dataset);
  H5Sclose(space);
  H5Fclose(file);
  H5Pclose(access);
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) std::filesystem::remove(path.data());
}

}  // namespace
