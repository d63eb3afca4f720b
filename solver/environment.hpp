#pragma once
// One simulation environment: a shared static Model and this environment's own state (DOFs,
// velocities, kinematic poses and scripts, gravity, barrier stiffness), advanced one implicit
// Euler step at a time by projected Newton. Every accepted step leaves every contact pair
// apart (distance > 0) and every tet positively oriented; a step that cannot do so fails the
// environment with a reason, and a failed environment stays failed.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>

#include "solver/engine/engine.hpp"
#include "solver/linear/linear_system_solver.hpp"
#include "solver/model/model.hpp"
#include "solver/newton/diagnostics.hpp"
#include "solver/newton/failure.hpp"
#include "solver/newton/newton_solver.hpp"
#include "solver/newton/step_policy.hpp"
#include "solver/potential/contact_forces.hpp"
#include "solver/scene/state.hpp"

namespace grip::solver {

// The CPU engine's environment (EnvironmentHandle): its state on the host, its Newton systems
// solved by CHOLMOD (or an attached LinearSystemSolver).
class Environment final : public EnvironmentHandle {
 public:
  explicit Environment(std::shared_ptr<const Model> model);
  ~Environment() override;
  Environment(Environment&&) noexcept;

  // Before the first step: moves a body rigidly by `motion` from where it is (in a fresh
  // environment, where the scene starts it); its velocities turn with it, scripts are left as
  // they are. Environments of one model
  // start apart this way, e.g. a gripper at each candidate's pose. A pinned FEM body and its
  // mount must be moved together. Throws std::logic_error after the first step.
  void place(int body, const Eigen::Isometry3d& motion) override;

  // Advances one time step; false when the environment failed (now or before).
  bool step();

  // The same step in parts, for a batch that runs the Newton iterations of many environments
  // in rounds: begin_step(), then iterate() until it no longer returns kIterating.
  // kConverged only comes when the policy holds converged steps open (StepPolicy).
  enum class Progress { kIterating, kStepDone, kFailed, kConverged };
  Progress begin_step();
  Progress iterate();

  // Finishes a step held open under a policy without freeze_converged (StepPolicy): iterate()
  // reports kConverged for such a step, and each further iterate() takes one more Newton step.
  Progress finish_held_step();

  // Before the first step (at time 0): fails the environment with kIntersectingStart when two
  // of its surfaces touch or cross; true when its start is free. begin_step checks this itself.
  bool check_start();

  // A step of this environment taken elsewhere: by an engine that steps many environments in
  // buffers of its own (solver/batch/parallel_engine.hpp), for which this environment is the
  // host handle between steps. What the step left becomes this environment's, as if step() had
  // taken it: the state, the step's diagnostics and outcome, the statistics, and the contacts
  // its potential ended with (so that vertex_contact_forces answers as after step()).
  struct AdoptedStep {
    State state;
    StepDiagnostics diagnostics;
    Failure failure = Failure::kNone;
    std::string message;                    // why it failed, for people ("t = ... s: ...")
    Vertices start_positions;               // the collision vertices at the start of its last part
    double h = 0.0;                         // its last part's length
    double kappa = 0.0;                     // the barrier stiffness it stepped with
    std::vector<FrictionContact> friction;  // its last friction lag's contacts
    long cg_iterations = 0;
  };
  // Throws std::logic_error while a step of its own is under way or once it has failed.
  void adopt_step(AdoptedStep step);

  // Departures from the default step, only for measuring what the defaults save (StepPolicy).
  void set_policy(const StepPolicy& policy) { policy_ = policy; }
  const StepPolicy& policy() const { return policy_; }

  // Between steps, the caller may redirect gravity and change kinematic scripts.
  void set_gravity(const Eigen::Vector3d& gravity) override { state_.gravity = gravity; }
  void set_script(int body, const Script& script) override;
  // Between steps: holds a dynamic body still where it is, as a fixture would, until release()
  // (a trial's object while the fingers close on it): an affine body whole, an FEM body by the
  // four vertices of its tet nearest its centre of mass, so that it still deforms around them.
  // The held DOFs' velocities are zeroed. Throws std::invalid_argument for a kinematic body.
  void hold(int body) override;
  void release(int body) override;

  // Newton systems of at least `min_dofs` rows (all DOFs, prescribed ones included) are solved
  // by `solver` instead of the environment's own sparse Cholesky; a failure of `solver` fails
  // the environment with its reason. Null detaches it. The solver must not serve environments
  // that step at the same time (on other threads).
  void use_linear_solver(std::shared_ptr<LinearSystemSolver> solver, int min_dofs) override;

  const Model& model() const override { return *model_; }
  double time() const override { return state_.time; }
  bool failed() const override { return failure_code_ != Failure::kNone; }
  // Why the environment failed: the code to decide on, and a message for people.
  Failure failure_code() const override { return failure_code_; }
  const std::string& failure() const override { return failure_; }
  const StepDiagnostics& last_step() const override { return diagnostics_; }
  const EnvironmentStatistics& statistics() const override { return statistics_; }
  // Where the steps' time went, by stage of the Newton iteration.
  const StageSeconds& stage_seconds() const override { return newton_.stages(); }
  // How the steps' Newton systems were solved.
  const LinearSolveCounts& linear_solves() const override { return newton_.linear_solves(); }

  const State& state() const { return state_; }
  const Eigen::VectorXd& dofs() const override { return state_.q; }
  const Eigen::VectorXd& velocities() const { return state_.v; }
  // World positions of the collision vertices (one row each).
  Vertices collision_positions() const override;
  // World positions of all vertices of one body (FEM: every vertex, including interior ones).
  Vertices body_vertices(int body) const override;
  // Centre of mass (the frame origin for kinematic bodies), its velocity, and the body's
  // rotation (affine: the rotation nearest its affine matrix; FEM: the best-fit rotation of its
  // vertices against the rest shape; kinematic: its pose).
  Eigen::Vector3d center_of_mass(int body) const override;
  Eigen::Vector3d center_of_mass_velocity(int body) const override;
  Eigen::Matrix3d rotation(int body) const override;
  // The smallest det F over the tets of every FEM body (1 without FEM).
  double min_volume_ratio() const override;
  // The exact distance between the surfaces of `bodies` and of body `other` now, if it is below
  // `search` (m); infinity otherwise. The broad phase's cost grows with `search`.
  double surface_distance(const std::vector<int>& bodies, int other, double search) const override;
  // The contact forces on every collision vertex at the current state (between steps); the
  // pairs come from the broad phase the environment keeps.
  VertexContactForces vertex_contact_forces() override;

 private:
  // A step of dt is taken as parts: one part normally; a part that fails is rolled back to its
  // start and replaced by two parts of half its length (at most max_step_halvings deep).
  struct StepPlan {
    double end_time = 0.0;  // the time the whole step ends at
    int halvings = 0;       // depth of the current part: its length is dt / 2^halvings
    State part_start;       // the state the current part started from
  };
  Progress begin_part();
  Progress retry_or_fail(const NewtonSolver::FailureReport& failure);
  Progress finish_converged_part();
  void finish_part();
  void finish_step();
  Progress fail(Failure code, const std::string& reason);
  void record_diagnostics();

  std::shared_ptr<const Model> model_;
  State state_;
  StepPolicy policy_;
  Failure failure_code_ = Failure::kNone;
  std::string failure_;
  StepDiagnostics diagnostics_;
  StepPlan plan_;
  EnvironmentStatistics statistics_;
  std::unique_ptr<NewtonStep> step_;  // while a step is under way
  // Between steps: every pair within d_hat of the state's positions, once found, handed on
  // from the step that ended there to the next (NewtonStep::near).
  std::optional<std::vector<ContactCandidate>> near_;
  NewtonSolver newton_;
};

}  // namespace grip::solver
