#pragma once
// What one grasp trial produced: the dataset's result for the candidate (record, trajectory,
// the soft object's stress at the settled grasp), the solver's reason when it failed, and,
// when asked for, every body's vertices and stress at each recorded frame (for VTK files).
#include <array>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "io/candidate_record.hpp"
#include "solver/newton/diagnostics.hpp"
#include "src/geometry/mesh.hpp"
#include "src/metrics/distance_metrics.hpp"

namespace grip::trial {

// Every body of the trial's scene at one recorded frame.
struct BodyFrame {
  double time = 0.0;                         // s
  std::vector<geometry::Vertices> vertices;  // per body, all its vertices (world, m)
  std::vector<Eigen::VectorXd> stress;       // per body: von Mises per tet (Pa); empty if not FEM
};

struct TrialOutcome {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  io::CandidateResult result;
  std::string failure_reason;          // the solver's message for kNewtonLimit / kNumerical
  std::vector<BodyFrame> body_frames;  // closing then validation frames, when asked for
  // [n]: steps that took n Newton iterations (solver::EnvironmentStatistics); not in the dataset.
  std::vector<long> steps_by_newton_iterations;
  // Where the solver's time went (solver::Environment::stage_seconds); not in the dataset.
  solver::StageSeconds stage_seconds;
  // How its Newton systems were solved (solver::Environment::linear_solves); not in the dataset.
  solver::LinearSolveCounts linear_solves;
  // D1/D2 of each gripper's own surface at the settled grasp, for a bimanual trial (the record's
  // d1/d2 are over both grippers' surfaces); empty for one gripper or no settled grasp.
  std::vector<metrics::DistanceMetrics> gripper_distances;
  // Closing ended with every finger within force_tolerance of grip_force or at the end of its
  // path (TrialParameters), and the object was released.
  bool closed = false;
  // Per finger, in the record's closing_forces order: whether closing left it at the end of its
  // path (a finger that closed on air, or ran out of travel before its force reached
  // grip_force); empty where closing did not end. Not in the dataset.
  std::vector<bool> closing_at_path_end;
  // How far the object's centre of mass moved from the candidate's start to the settled grasp
  // (m); NaN for a trial that did not settle.
  double settle_displacement = nan;
  // The object's centre-of-mass displacement from the settled grasp after each gravity phase (m),
  // sag and slip together (the record's `displacement` is the slip alone); NaN for phases not run.
  std::array<double, 6> center_displacement = {nan, nan, nan, nan, nan, nan};
  // The object's largest centre-of-mass speed over the last kEndSpeedSteps steps of each gravity
  // phase (m/s); NaN for phases not run. An object held by static friction creeps at most at
  // about eps_v; one that swings on compliant fingers or slides moves orders of magnitude faster
  // (docs/trial.md, "Verdict"). Not in the dataset.
  std::array<double, 6> end_speed = {nan, nan, nan, nan, nan, nan};
  static constexpr int kEndSpeedSteps = 3;
};

}  // namespace grip::trial
