#pragma once
// The JSON report of `grip trial` (docs/trial.md): the batch's object, gripper, threads and wall
// time, the comparison with solo runs when asked for, and per candidate its verdict, the
// solver's reason, D1/D2, displacements, closing forces, Newton statistics and wall time; for a
// bimanual trial also each gripper's closing forces and D1/D2.
#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "src/grippers/fin_ray_finger.hpp"
#include "src/trial/trial_outcome.hpp"

namespace grip::trial {

struct TrialReport {
  std::string object;  // the object's spec, as given
  std::string gripper;
  // A fin-ray gripper's finger, whose mesh (layers, edge_length) the report records.
  std::optional<grippers::FinRayOptions> fin_ray;
  bool soft = false;
  int grippers = 1;  // 2: a bimanual trial, reported per gripper too
  int threads = 1;
  std::string device = "cpu";  // the engine (grip trial --device)
  double wall_seconds = 0.0;
  bool compared_solo = false;  // the candidates were also run one by one:
  double solo_wall_seconds = 0.0;
  bool identical_to_solo = true;
  // Peak resident memory above the start (MiB): the batch's, and the largest of one alone.
  double batch_memory_mib = 0.0;
  double solo_memory_mib = 0.0;
  // What each candidate after the first added to the batch's peak (MiB); `candidates` > 1.
  double memory_per_added_environment_mib(std::size_t candidates) const {
    return (batch_memory_mib - solo_memory_mib) / static_cast<double>(candidates - 1);
  }
};

void write_report(std::ostream& out, const TrialReport& report,
                  const std::vector<TrialOutcome>& outcomes);

}  // namespace grip::trial
