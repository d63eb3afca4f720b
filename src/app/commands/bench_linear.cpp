// grip bench linear: where PETSc across MPI ranks starts to beat one core's CHOLMOD
// (bench/linear/linear_benchmark.hpp, docs/linear-solvers.md).
#include <mpi.h>

#include <iostream>

#include "bench/linear/linear_benchmark.hpp"
#include "farm/petsc/petsc_session.hpp"
#include "farm/petsc/petsc_system_solver.hpp"
#include "src/app/commands.hpp"

namespace grip::commands {

int bench_linear(const BenchLinearArgs& args) {
  MPI_Init(nullptr, nullptr);
  {
    const farm::PetscSession petsc_session(args.petsc_options);
    farm::PetscSystemSolver petsc(MPI_COMM_WORLD);
    bench::LinearBenchmarkOptions options;
    options.source = args.system == "squeeze" ? bench::LinearSystemSource::kSqueeze
                                              : bench::LinearSystemSource::kBimanualTrial;
    options.cells = args.cells;
    options.repeats = args.repeats;
    const bench::LinearBenchmarkResult result =
        bench::run_linear_benchmark(petsc, options, std::cout, MPI_COMM_WORLD);
    if (petsc.rank() == 0) bench::write_json_line(std::cout, result);
  }
  MPI_Finalize();
  return 0;
}

}  // namespace grip::commands
