// grip bench peer: the same parallel-jaw or LEAP-hand candidates validated by grip and by MuJoCo
// (bench/peer/peer_benchmark.hpp, docs/results.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "bench/peer/mujoco_trial.hpp"
#include "bench/peer/peer_benchmark.hpp"
#include "bench/peer/peer_report.hpp"
#include "src/app/commands.hpp"

namespace grip::commands {

int bench_peer(const BenchPeerArgs& args) {
  bench::PeerOptions options;
  options.gripper = args.gripper;
  options.categories = args.categories;
  options.seeds = args.seeds;
  options.candidates = args.candidates;
  options.threads = args.threads;
  options.out = args.out;
  options.vtk = args.vtk;
  try {
    bench::check_peer_options(options);
  } catch (const std::invalid_argument& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  if (!bench::mujoco_available()) {
    spdlog::error(
        "grip bench peer: this grip was built without MuJoCo; apt-get install libmujoco-dev, "
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

}  // namespace grip::commands
