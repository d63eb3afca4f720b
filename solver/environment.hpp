#pragma once
// One simulation environment: a shared static Model and this environment's own state (DOFs,
// velocities, kinematic poses and scripts, gravity, barrier stiffness), advanced one implicit
// Euler step at a time by projected Newton. Every accepted step leaves every contact pair
// apart (distance > 0) and every tet positively oriented; a step that cannot do so fails the
// environment with a reason, and a failed environment stays failed.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "solver/linear/linear_system_solver.hpp"
#include "solver/linear/sparse_assembly.hpp"
#include "solver/linear/sparse_cholesky.hpp"
#include "solver/model.hpp"
#include "solver/newton/incremental_potential.hpp"

namespace grip::solver {

// The total contact force (barrier and friction) that body_b exerts on body_a, body_a < body_b.
struct PairForce {
  int body_a = -1;
  int body_b = -1;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // on body_a, N
  double normal_force = 0.0;  // sum of the contacts' barrier force magnitudes, N
};

// Contact forces on each collision vertex (rows follow Model::collision()), N.
struct VertexContactForces {
  Vertices normal;    // barrier (normal) force
  Vertices friction;  // lagged friction force of the last step
};

struct StepDiagnostics {
  int newton_iterations = 0;
  int line_search_steps = 0;  // Armijo halvings and inversion halvings
  double min_distance = std::numeric_limits<double>::infinity();  // over pairs within d_hat
  double min_volume_ratio = 1.0;  // smallest det F over all tets (1 without FEM)
  double kappa = 0.0;
  int friction_contacts = 0;  // lagged friction contacts of the last lag
  double residual =
      0.0;  // infinity norm of the free DOFs' gradient at the end, scaled by 1/h^2 (N)
  std::vector<PairForce> contact_forces;
};

// Totals over every step an environment has taken.
struct EnvironmentStatistics {
  long steps = 0;
  long newton_iterations = 0;
  int max_step_iterations = 0;  // most Newton iterations in one step
};

class Environment {
 public:
  explicit Environment(std::shared_ptr<const Model> model);
  ~Environment();
  Environment(Environment&&) noexcept;

  // Before the first step: moves a body rigidly by `motion` from where the scene starts it
  // (its velocities turn with it; scripts are left as they are). Environments of one model
  // start apart this way, e.g. a gripper at each candidate's pose. A pinned FEM body and its
  // mount must be moved together. Throws std::logic_error after the first step.
  void place(int body, const Eigen::Isometry3d& motion);

  // Advances one time step; false when the environment failed (now or before).
  bool step();

  // The same step in parts, for a batch that runs the Newton iterations of many environments
  // in rounds: begin_step(), then iterate() until it no longer returns kIterating.
  // kConverged only comes with hold_converged (below).
  enum class Progress { kIterating, kStepDone, kFailed, kConverged };
  Progress begin_step();
  Progress iterate();

  // Off by default. On, a step whose Newton converged is held open instead of finished, the
  // way one global convergence test of a monolithic solver keeps every part iterating until
  // the slowest converges: iterate() reports kConverged, each further iterate() takes one more
  // Newton step from there (and reports kConverged again), and finish_held_step() ends the step.
  // A held step has no iteration limit (the slowest environment's bounds it), and its line
  // search does not halve for its own energy (in a monolithic solve that energy is one term of
  // a sum whose decrease decides). step() finishes a held step itself. Only for measuring what
  // freezing converged environments saves (Batch::set_freeze_converged).
  void set_hold_converged(bool hold) { hold_converged_ = hold; }
  Progress finish_held_step();

  // Off by default: contact pairs with mu = 0 get no friction terms. On, they get them anyway
  // (each adds zero force at the full cost of its lag and its derivatives); only for measuring
  // what skipping them saves.
  void set_friction_terms_at_zero_mu(bool on) { friction_terms_at_zero_mu_ = on; }

  // Between steps, the caller may redirect gravity and change kinematic scripts.
  void set_gravity(const Eigen::Vector3d& gravity) { gravity_ = gravity; }
  void set_script(int body, const Script& script);

  // Newton systems of at least `min_dofs` rows (all DOFs, prescribed ones included) are solved
  // by `solver` instead of the environment's own sparse Cholesky; a failure of `solver` fails
  // the environment with its reason. Null detaches it. The solver must not serve environments
  // that step at the same time (on other threads).
  void use_linear_solver(std::shared_ptr<LinearSystemSolver> solver, int min_dofs);

  const Model& model() const { return *model_; }
  double time() const { return time_; }
  bool failed() const { return !failure_.empty(); }
  const std::string& failure() const { return failure_; }
  const StepDiagnostics& last_step() const { return diagnostics_; }
  const EnvironmentStatistics& statistics() const { return statistics_; }

  const Eigen::VectorXd& dofs() const { return q_; }
  const Eigen::VectorXd& velocities() const { return v_; }
  // World positions of the collision vertices (one row each).
  Vertices collision_positions() const;
  // World positions of all vertices of one body (FEM: every vertex, including interior ones).
  Vertices body_vertices(int body) const;
  // Centre of mass (the frame origin for kinematic bodies), its velocity, and the body's
  // rotation (affine: the rotation nearest its affine matrix; FEM: the best-fit rotation of its
  // vertices against the rest shape; kinematic: its pose).
  Eigen::Vector3d center_of_mass(int body) const;
  Eigen::Vector3d center_of_mass_velocity(int body) const;
  Eigen::Matrix3d rotation(int body) const;
  // The smallest det F over the tets of every FEM body (1 without FEM).
  double min_volume_ratio() const;
  // The contact forces on every collision vertex at the current state (between steps).
  VertexContactForces vertex_contact_forces() const;

 private:
  struct StepTargets;
  struct StepState;
  enum class NewtonOutcome { kContinue, kConverged, kFailed };
  Vertices positions_at(const Eigen::VectorXd& q, const StepTargets& targets,
                        double progress) const;
  std::vector<FrictionContact> lag_friction(const Vertices& positions) const;
  NewtonOutcome newton_iteration(StepState& state);
  void finish_step();
  Progress fail(const std::string& reason);
  void record_diagnostics(const StepTargets& targets);

  std::shared_ptr<const Model> model_;
  Eigen::VectorXd q_;
  Eigen::VectorXd v_;
  std::vector<Pose> poses_;  // kinematic bodies' current poses (others unused)
  std::vector<Eigen::Vector3d> kinematic_velocity_;  // over the last step
  std::vector<Script> scripts_;
  Eigen::Vector3d gravity_;
  double kappa_;
  double time_ = 0.0;
  std::string failure_;
  StepDiagnostics diagnostics_;
  EnvironmentStatistics statistics_;
  std::unique_ptr<StepState> step_;  // while a step is under way
  IncrementalPotential potential_;
  SparseAssembly assembly_;
  SparseCholesky cholesky_;
  std::shared_ptr<LinearSystemSolver> linear_solver_;  // null: cholesky_ solves every system
  int linear_solver_min_dofs_ = 0;
  bool hold_converged_ = false;
  bool friction_terms_at_zero_mu_ = false;
};

}  // namespace grip::solver
