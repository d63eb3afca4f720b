#pragma once
// The grasp trial protocol shared by every gripper (GRIP, Sec. III-D): what the protocol needs
// from one gripper's scene and candidates (TrialGripper), and run_protocol, which steps them as
// one solver::Engine through closing, settling and the six gravity phases to their outcomes.
// Callers run trials through src/trial/trial.hpp (run_trials), which builds the TrialGripper.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "solver/batch/engines.hpp"
#include "solver/engine/engine.hpp"
#include "solver/linear/linear_system_solver.hpp"
#include "solver/model/model.hpp"
#include "src/geometry/mesh.hpp"
#include "src/metrics/distance_metrics.hpp"
#include "src/trial/trial_outcome.hpp"
#include "src/trial/trial_parameters.hpp"
#include "src/trial/trial_scene.hpp"

namespace grip::trial {

struct TrialRunOptions {
  int threads = 0;  // the batch's threads; 0: all cores. Results do not depend on it.
  // The engine that steps the trials: the CPU engine, or the data-parallel engine on the host
  // launcher (its numerics differ: docs/simulation.md, "The engine seam").
  solver::EngineDevice device = solver::EngineDevice::kCpu;
  bool trajectory = true;          // fill CandidateResult::trajectory
  bool body_frames = false;        // fill TrialOutcome::body_frames (all bodies, stress; for VTK)
  std::vector<std::uint64_t> ids;  // record ids per candidate; empty: 0, 1, 2, ...
  // Trials stepping at once; the next candidate starts as soon as one ends, so no thread waits
  // for a batch's slowest trial. 0: every candidate at once. Results do not depend on it.
  int max_active = 0;
  // Called on the calling thread after every step of the batch with how many of its trials
  // have ended so far (the farm's live progress). Results do not depend on it.
  std::function<void(std::size_t ended)> after_step;
  // A trial stops once its verdict is decided (a gravity phase's end found the object dropped
  // or slipped past the threshold): no later phase can change it. True: such a trial runs the
  // six phases to the end all the same (frames of a failed grasp to the end); the verdicts are
  // the same either way (docs/trial.md, "Verdict").
  bool full_trials = false;
  // Every Newton system of these trials goes to this solver instead of their environments' own
  // CHOLMOD (the farm's PETSc group, for a model too big for one rank). It serves one system at
  // a time and may talk MPI: it needs threads = 1 and the CPU engine. Null: CHOLMOD solves every
  // system.
  std::shared_ptr<solver::LinearSystemSolver> big_system_solver;
};

// One gripper's side of a batch of trials: its scene (object, fingers, measurements) and its
// candidates. Each finger closes along a path of its own, measured by its travel (m) from the
// candidate's start: a parallel jaw along the closing axis, a hand's finger through its joints.
// A bimanual trial is one TrialGripper with both grippers' fingers, the first gripper's first.
class TrialGripper {
 public:
  virtual ~TrialGripper() = default;

  virtual const TrialParameters& parameters() const = 0;
  virtual const std::shared_ptr<const solver::Model>& model() const = 0;
  virtual bool soft_object() const = 0;
  virtual int object_body() const = 0;
  virtual std::size_t candidate_count() const = 0;
  virtual int finger_count() const = 0;
  // The bodies whose normal contact force with the object is the finger's force.
  virtual const std::vector<int>& finger_bodies(int finger) const = 0;

  // Puts candidate k in a fresh environment (gravity off, fingers held) and returns each
  // finger's longest travel (m). Throws std::out_of_range for a candidate the gripper cannot take.
  virtual std::vector<double> place(solver::EnvironmentHandle& environment,
                                    std::size_t k) const = 0;
  // Before the first step: moves the finger along its closing path from travel `from` to `to`.
  virtual void place_finger(solver::EnvironmentHandle& environment, std::size_t k, int finger,
                            double from, double to) const = 0;
  // Moves the finger over the next step from `travel` on at `speed` (m/s), or holds it.
  virtual void move_finger(solver::EnvironmentHandle& environment, std::size_t k, int finger,
                           double travel, double speed) const = 0;
  virtual void hold_finger(solver::EnvironmentHandle& environment, int finger) const = 0;
  // The fingers' drives are springs inside the solve (driven bodies, BodyDescription::
  // drive_stiffness): after closing, a finger is halted where its command stands. Otherwise it
  // is kinematic and held as a spring by the protocol, a step behind.
  virtual bool driven_fingers() const { return false; }

  // The candidate's pose per gripper (world from gripper; one, or two for a bimanual trial) and
  // joint values (the dataset's layout: the grippers' one after the other), and the joint values
  // when its fingers have travelled `travel`.
  virtual std::vector<Eigen::Isometry3d> poses(std::size_t k) const = 0;
  virtual std::vector<double> joints(std::size_t k, const std::vector<double>& travel) const = 0;

  // The gripper's surface vertices in the dataset's order, now.
  virtual geometry::Vertices surface_vertices(
      const solver::EnvironmentHandle& environment) const = 0;
  // Where each of those vertices lives: its body and its index among the body's vertices.
  virtual std::vector<BodyVertex> surface_sources() const = 0;
  // The object's pose now: row-major 3x4 [A | t], world from object frame.
  virtual std::array<double, 12> object_pose(
      const solver::EnvironmentHandle& environment) const = 0;
  // D1/D2 now, from points fixed on the gripper's surface (both grippers' for a bimanual
  // trial), and per gripper for a bimanual trial (empty for one gripper).
  virtual metrics::DistanceMetrics grasp_distances(
      const solver::EnvironmentHandle& environment) const = 0;
  virtual std::vector<metrics::DistanceMetrics> gripper_distances(
      const solver::EnvironmentHandle&) const {
    return {};
  }
  // Von Mises stress per tet of one body now (Pa); empty for a body that is not FEM.
  virtual Eigen::VectorXd body_stress(const solver::EnvironmentHandle& environment,
                                      int body) const = 0;
  // Von Mises stress per tet of the soft fingers now (Pa), in the order of the gripper record's
  // tets; empty when the fingers are rigid.
  virtual Eigen::VectorXd finger_stress(const solver::EnvironmentHandle&) const { return {}; }
};

// One outcome per candidate, in order; each record's wall_time is the batch's wall time divided
// by the number of candidates (a batch does not time its environments one by one). Throws
// std::invalid_argument when options.ids does not give one id per candidate, and
// std::out_of_range naming a candidate the gripper cannot take.
std::vector<TrialOutcome> run_protocol(const TrialGripper& gripper, const TrialRunOptions& options);

}  // namespace grip::trial
