#pragma once
// An existing dataset read once in a child process (grip itself, started in a hidden mode)
// before grip reads it for real: a file that crashes HDF5 inside the library becomes one error
// naming the file instead of a crash of grip (docs/testing.md, "Damaged HDF5 files").
#include <filesystem>

namespace grip {

// The hidden mode's first argument: `grip --probe-dataset FILE` reads FILE the way `grip
// inspect` does and exits 0 (read), 1 (refused with an error) or dies with HDF5.
inline constexpr const char* kProbeDatasetMode = "--probe-dataset";
int probe_dataset(const char* file);

// Starts `grip --probe-dataset FILE` (posix_spawn: safe after MPI_Init) and waits for it.
// Throws io::DatasetError naming the file when the child was killed by a signal; returns
// otherwise, leaving any error the reader reports to the caller's own read.
void check_dataset_readable(const std::filesystem::path& file);

}  // namespace grip
