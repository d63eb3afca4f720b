#include "solver/linear/blas_threads.hpp"

#include <dlfcn.h>

namespace grip::solver {
namespace {

// Looked up at run time: the BLAS is chosen by the system (Debian's alternatives), the
// reference BLAS has no such function, and the OpenMP runtime is CHOLMOD's, not grip's.
using SetInt = void (*)(int);
SetInt lookup(const char* name) { return reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, name)); }

}  // namespace

void use_single_threaded_blas() {
  if (const SetInt set = lookup("openblas_set_num_threads")) set(1);
}

void use_single_threaded_openmp() {
  static const SetInt set_max_active_levels = lookup("omp_set_max_active_levels");
  if (set_max_active_levels) set_max_active_levels(0);
}

}  // namespace grip::solver
