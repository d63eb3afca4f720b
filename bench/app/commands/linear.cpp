// grip bench linear: where PETSc across MPI ranks starts to beat one core's CHOLMOD
// (bench/linear/linear_benchmark.hpp, docs/linear-solvers.md).
#include <mpi.h>

#include <iostream>
#include <memory>

#include "app/cli/command_line.hpp"
#include "bench/app/commands.hpp"
#include "bench/linear/linear_benchmark.hpp"
#include "farm/petsc/petsc_session.hpp"
#include "farm/petsc/petsc_system_solver.hpp"

namespace grip::commands {
namespace {

// grip bench linear [--cells 0.01,0.006,...] [--repeats N] [-- PETSc options]: CHOLMOD against
// PETSc's KSP on Newton systems of growing size, on the ranks it runs with (bench/linear/,
// docs/linear-solvers.md).
struct BenchLinearArgs {
  std::string system = "bimanual-trial";  // or "squeeze" (bench/linear/linear_benchmark.hpp)
  std::vector<double> cells{0.01, 0.006, 0.004, 0.003, 0.0025};  // tet cell sizes (m)
  int repeats = 5;
  std::vector<std::string> petsc_options;  // after a lone `--`
};

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

}  // namespace

void declare_bench_linear(cli::Command& group) {
  auto args = std::make_shared<BenchLinearArgs>();
  cli::Command linear = group.subcommand(
      "linear",
      "CHOLMOD against PETSc on Newton systems by size, under mpirun (docs/linear-solvers.md)");
  linear
      .option("--system", args->system,
              "Newton systems of a bimanual soft trial (a long bar) or of a squeezed cube")
      .show_default()
      .check(cli::Check::one_of({"bimanual-trial", "squeeze"}));
  linear.option("--cells", args->cells, "Tet cell sizes (m), e.g. 0.01,0.004")
      .list()
      .show_default()
      .check(cli::Check::positive());
  linear.option("--repeats", args->repeats, "Timed solves per size (median)")
      .check(cli::Check::positive_count())
      .show_default();
  linear.takes_petsc_options(args->petsc_options);
  linear.on_run([args] { return bench_linear(*args); });
}

}  // namespace grip::commands
