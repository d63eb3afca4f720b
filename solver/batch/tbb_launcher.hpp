#pragma once
// The host launcher the CPU runs the data-parallel engine's stages with
// (solver/parallel/launch.hpp): items spread over a TBB arena's threads in chunks.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include <numeric>

namespace grip::solver::parallel {

class TbbLauncher {
 public:
  // threads = 0: all the machine's cores.
  explicit TbbLauncher(int threads = 0)
      : arena_(threads > 0 ? threads : tbb::this_task_arena::max_concurrency()) {}

  template <class Stage>
  void operator()(int count, const Stage& stage) {
    arena_.execute([&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, count, kGrain),
                        [&](const tbb::blocked_range<int>& range) {
                          for (int i = range.begin(); i < range.end(); ++i) stage(i);
                        });
    });
  }

  template <class T>
  T fetch(const T* value) const {
    return *value;
  }
  template <class Less>
  void sort(int* items, int count, const Less& less) {
    arena_.execute([&] { tbb::parallel_sort(items, items + count, less); });
  }
  void exclusive_scan(int* values, int count) const {
    std::exclusive_scan(values, values + count, values, 0);
  }

 private:
  static constexpr int kGrain = 64;  // items per task: a tet's stage is about a microsecond
  tbb::task_arena arena_;
};

}  // namespace grip::solver::parallel
