#include "solver/linear/blas_threads.hpp"

#include <dlfcn.h>

namespace grip::solver {

void use_single_threaded_blas() {
  // Looked up at run time: the BLAS is chosen by the system (Debian's alternatives), and the
  // reference BLAS has no such function.
  using SetThreads = void (*)(int);
  if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) {
    set(1);
  }
}

}  // namespace grip::solver
