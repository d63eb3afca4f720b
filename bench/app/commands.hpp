#pragma once
// The benchmark program's commands (grip-bench, which `grip bench` and `grip ccd-bench` run):
// each file of bench/app/commands/ declares one benchmark, its options beside the arguments they
// fill, and runs it. bench/app/main.cpp declares them in the order `grip bench --help` lists
// them.
namespace grip::cli {
class Command;
}  // namespace grip::cli

namespace grip::commands {

void declare_ccd_bench(cli::Command& root);  // grip ccd-bench (ccd_bench.cpp)
// The `bench` group's commands, one file each.
void declare_bench_batch(cli::Command& group);
void declare_bench_scaling(cli::Command& group);
void declare_bench_scale(cli::Command& group);
void declare_bench_scale_probe(cli::Command& group);  // in scale.cpp
void declare_bench_accuracy(cli::Command& group);
void declare_bench_hard(cli::Command& group);
void declare_bench_model(cli::Command& group);
void declare_bench_robustness(cli::Command& group);
void declare_bench_labels(cli::Command& group);
void declare_bench_peer(cli::Command& group);
void declare_bench_trial(cli::Command& group);
void declare_bench_cost(cli::Command& group);
void declare_bench_linear(cli::Command& group);

}  // namespace grip::commands
