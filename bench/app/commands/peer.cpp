// grip bench peer: the same parallel-jaw, fin-ray or LEAP-hand candidates validated by grip and by
// MuJoCo (bench/peer/peer_benchmark.hpp, docs/results.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "app/cli/command_line.hpp"
#include "bench/app/commands.hpp"
#include "bench/peer/mujoco_trial.hpp"
#include "bench/peer/peer_benchmark.hpp"
#include "bench/peer/peer_report.hpp"

namespace grip::commands {
namespace {

// grip bench peer [--gripper G] [--categories ...] [--seeds N] [--candidates N] [--threads N]
// [--out DIR] [--vtk DIR]: the same parallel-jaw, fin-ray or LEAP-hand candidates validated by grip
// and by MuJoCo (bench/peer/, docs/results.md).
struct BenchPeerArgs {
  std::string gripper = "parallel-jaw";  // or fin-ray, leap
  std::vector<std::string> categories;   // empty: box, cylinder, capsule, bottle, sphere, ellipsoid
  int seeds = 4;                         // shapes per category
  int candidates = 9;                    // per shape
  int threads = 1;                       // grip's trial
  std::string out = "out/peer";
  std::string vtk;  // the disagreement examples as VTK; empty: none
  bool mujoco_ipc = false;
};

int bench_peer(const BenchPeerArgs& args) {
  bench::PeerOptions options;
  options.gripper = args.gripper;
  options.categories = args.categories;
  options.seeds = args.seeds;
  options.candidates = args.candidates;
  options.threads = args.threads;
  options.out = args.out;
  options.vtk = args.vtk;
  options.mujoco_ipc = args.mujoco_ipc;
  try {
    bench::check_peer_options(options);
  } catch (const std::invalid_argument& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  if (!bench::mujoco_available()) {
    spdlog::error(
        "grip bench peer: this grip was built without MuJoCo; run scripts/install-peers.sh, "
        "then configure and build again");
    return 1;
  }
  const bench::PeerResult result = bench::run_peer(options);
  const std::vector<bench::PeerTally> tallies = bench::peer_tallies(result);
  std::cout << "\n";
  bench::write_peer_table(std::cout, tallies);
  bench::write_peer_files(options.out, result, tallies);
  const std::string stem = bench::peer_file_stem(result.gripper);
  std::printf("tables: %s/%s.md, candidates: %s/%s.csv\n", args.out.c_str(), stem.c_str(),
              args.out.c_str(), stem.c_str());
  for (const std::string& v : result.vtk) std::printf("VTK: %s/%s\n", args.vtk.c_str(), v.c_str());
  bench::write_peer_json_line(std::cout, result, tallies);
  return 0;
}

}  // namespace

void declare_bench_peer(cli::Command& group) {
  auto args = std::make_shared<BenchPeerArgs>();
  cli::Command peer = group.subcommand(
      "peer",
      "The same parallel-jaw, fin-ray or LEAP-hand candidates validated by grip and by MuJoCo "
      "(D1, D2, penetration, verdicts)");
  peer.option("--gripper", args->gripper, "parallel-jaw, fin-ray or leap")
      .check(cli::Check::one_of({"parallel-jaw", "fin-ray", "leap"}))
      .show_default();
  peer.option("--categories", args->categories,
              "Object categories (default: box,cylinder,capsule,bottle,sphere,ellipsoid)")
      .list();
  peer.option("--seeds", args->seeds, "Shapes per category")
      .check(cli::Check::positive_count())
      .show_default();
  peer.option("--candidates", args->candidates, "Candidates per shape")
      .check(cli::Check::positive_count())
      .show_default();
  peer.option("--threads", args->threads, "Threads of grip's trial")
      .check(cli::Check::positive_count())
      .show_default();
  peer.option("--out", args->out,
              "Folder for peer.md and peer.csv (the others': peer-GRIPPER.md, peer-GRIPPER.csv)")
      .show_default()
      .check(cli::Check::output_folder());
  peer.option("--vtk", args->vtk,
              "Folder for the first candidate of each kind of disagreement as VTK")
      .check(cli::Check::output_folder());
  peer.flag("--mujoco-ipc", args->mujoco_ipc,
            "The fin-ray: MuJoCo's scenes with its experimental IPC contact mode");
  peer.on_run([args] { return bench_peer(*args); });
}

}  // namespace grip::commands
