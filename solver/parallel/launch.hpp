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

namespace grip::solver::parallel {

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
