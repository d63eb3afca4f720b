// grip-bench: the benchmarks, a program of their own so that building `grip` (the demo's first
// build) compiles none of them. `grip bench ...` and `grip ccd-bench ...` run it with their
// whole command line; it speaks as grip.
#include "app/cli/command_line.hpp"
#include "bench/app/commands.hpp"

int main(int argc, char** argv) {
  grip::cli::Program program;
  program.name = "grip";
  program.description =
      "grip's benchmarks (grip bench, grip ccd-bench).\n"
      "PETSc options follow a lone '--' (e.g. grip bench linear -- -ksp_type cg).";
  program.declare = [](grip::cli::Command& root) {
    using namespace grip::commands;
    declare_ccd_bench(root);
    grip::cli::Command bench = root.subcommand("bench", "Benchmarks of whole subsystems");
    bench.require_subcommand();
    for (const auto declare :
         {declare_bench_batch, declare_bench_scaling, declare_bench_scale,
          declare_bench_scale_probe, declare_bench_accuracy, declare_bench_hard,
          declare_bench_model, declare_bench_robustness, declare_bench_labels, declare_bench_peer,
          declare_bench_trial, declare_bench_cost, declare_bench_linear}) {
      declare(bench);
    }
  };
  return grip::cli::run_program(program, argc, argv);
}
