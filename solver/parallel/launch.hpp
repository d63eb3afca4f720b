#pragma once
// One source, two launchers. A stage of the data-parallel engine is a functor whose GRIP_HD
// operator()(int i) computes item i (a tet, a contact pair, a vertex) of flat buffers that hold
// every environment of a batch, reading and writing only through the raw pointers it carries.
// A launcher runs a stage for every i in [0, count): SerialLauncher and TbbLauncher
// (solver/batch/tbb_launcher.hpp) on the host, CudaLauncher (cuda/cuda_launcher.cuh) on a GPU.
// Items are independent, so the host launchers give the same values bit for bit, and a GPU the
// same to round-off (it contracts multiply-adds); reductions over items are stages of their
// own, in a fixed order, never atomics. A launcher's fetch() reads one value of its memory to
// the host: what a host loop needs to decide whether to go on. Its sort() (by a total order, so
// any algorithm gives the same result) and exclusive_scan() (of ints, in place) are the
// standard library's on the host and Thrust's on a GPU.
#include <algorithm>
#include <numeric>
#include <vector>

#include "solver/kernels/hd.hpp"

namespace grip::solver::parallel {

// Host memory, as the storage templates that take host or device arrays name it (DeviceArray,
// cuda/cuda_launcher.cuh, is the other).
template <class T>
using HostArray = std::vector<T>;

// How many of `count` items have status `value`, into *out: one item, for a host loop's fetch().
struct StatusCountStage {
  const int* status = nullptr;
  int count = 0;
  int value = 0;
  int* out = nullptr;

  GRIP_HD void operator()(int) const {
    int n = 0;
    for (int i = 0; i < count; ++i) n += status[i] == value ? 1 : 0;
    *out = n;
  }
};

// The environment e whose range [begin[e], begin[e + 1]) of items holds item i (binary search
// over the environments + 1 offsets).
GRIP_HD inline int environment_of(const int* begin, int environment_count, int i) {
  int low = 0, high = environment_count - 1;
  while (low < high) {
    const int mid = (low + high + 1) / 2;
    if (begin[mid] <= i) {
      low = mid;
    } else {
      high = mid - 1;
    }
  }
  return low;
}

// The host launcher without dependencies: the device check's reference, and what the tests use
// to step through a stage.
struct SerialLauncher {
  template <class Stage>
  void operator()(int count, const Stage& stage) const {
    for (int i = 0; i < count; ++i) stage(i);
  }
  template <class T>
  T fetch(const T* value) const {
    return *value;
  }
  template <class Less>
  void sort(int* items, int count, const Less& less) const {
    std::sort(items, items + count, less);
  }
  void exclusive_scan(int* values, int count) const {
    std::exclusive_scan(values, values + count, values, 0);
  }
};

}  // namespace grip::solver::parallel
