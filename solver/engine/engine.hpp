#pragma once
// The seam between the trial protocol and an engine that steps many IPC environments at once
// (GRIP, Section III-A). An engine holds a batch of environments, each built from a shared
// static Model; between steps its caller places bodies, sets scripts and gravity, holds and
// releases bodies, and reads positions, forces, statistics and failures through each
// environment's handle. The CPU engine (solver::Batch of solver::Environment) is the first
// implementation; an engine whose state lives elsewhere (a device) keeps a host handle per
// environment, synchronised at step boundaries, so that everything read or set through the
// handle happens between steps.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "solver/linear/linear_system_solver.hpp"
#include "solver/model/model.hpp"
#include "solver/newton/diagnostics.hpp"
#include "solver/newton/failure.hpp"
#include "solver/newton/step_policy.hpp"
#include "solver/potential/contact_forces.hpp"
#include "solver/scene/state.hpp"

namespace grip::solver {

// One environment of an engine, as its caller sees it between steps.
class EnvironmentHandle {
 public:
  virtual ~EnvironmentHandle() = default;

  // Before the first step: moves a body rigidly by `motion` from where it is; its velocities
  // turn with it. Throws std::logic_error after the first step.
  virtual void place(int body, const Eigen::Isometry3d& motion) = 0;
  // Between steps: gravity, a kinematic or driven body's script, and holding a dynamic body
  // still where it is (Environment::hold) until it is released.
  virtual void set_gravity(const Eigen::Vector3d& gravity) = 0;
  virtual void set_script(int body, const Script& script) = 0;
  virtual void hold(int body) = 0;
  virtual void release(int body) = 0;
  // Newton systems of at least `min_dofs` rows go to `solver` (Environment::use_linear_solver).
  virtual void use_linear_solver(std::shared_ptr<LinearSystemSolver> solver, int min_dofs) = 0;

  virtual const Model& model() const = 0;
  virtual double time() const = 0;
  // A failed environment stays failed: the code to decide on, and a message for people.
  virtual bool failed() const = 0;
  virtual Failure failure_code() const = 0;
  virtual const std::string& failure() const = 0;
  virtual const StepDiagnostics& last_step() const = 0;
  virtual const EnvironmentStatistics& statistics() const = 0;
  virtual const StageSeconds& stage_seconds() const = 0;
  virtual const LinearSolveCounts& linear_solves() const = 0;

  virtual const Eigen::VectorXd& dofs() const = 0;
  // World positions of the collision vertices, and of all vertices of one body.
  virtual Vertices collision_positions() const = 0;
  virtual Vertices body_vertices(int body) const = 0;
  virtual Eigen::Vector3d center_of_mass(int body) const = 0;
  virtual Eigen::Vector3d center_of_mass_velocity(int body) const = 0;
  virtual Eigen::Matrix3d rotation(int body) const = 0;
  // The smallest det F over every FEM tet (1 without FEM).
  virtual double min_volume_ratio() const = 0;
  // The exact distance between the surfaces of `bodies` and of body `other` if below `search`.
  virtual double surface_distance(const std::vector<int>& bodies, int other,
                                  double search) const = 0;
  // The contact forces on every collision vertex at the current state.
  virtual VertexContactForces vertex_contact_forces() = 0;
};

// What one engine step cost: rounds of Newton iterations, and per round how many environments
// iterated and how many sat frozen (converged this step, while others still iterated).
struct BatchStepReport {
  int stepped = 0;  // environments that took part in the step
  int rounds = 0;
  long iterations = 0;  // environment-iterations over all rounds
  long frozen = 0;      // environment-rounds spent frozen
  int failed = 0;       // environments that failed in this step
};

// A batch of environments stepped together. No environment's step size, tolerance, iterations
// or failure changes another's result: each gets what it gets when run alone on the engine.
class Engine {
 public:
  virtual ~Engine() = default;

  // Adds an environment of `model` and returns its index.
  virtual int add(std::shared_ptr<const Model> model) = 0;
  virtual EnvironmentHandle& environment(int index) = 0;
  virtual const EnvironmentHandle& environment(int index) const = 0;
  virtual int size() const = 0;
  // The host threads the engine steps its environments on (and its caller may use between
  // steps).
  virtual int threads() const = 0;

  // Takes an environment out of further steps (its trial is over); it keeps its state.
  virtual void retire(int index) = 0;
  // Not retired and not failed.
  virtual bool active(int index) const = 0;
  virtual bool any_active() const = 0;

  // The step policy of every environment, present and future (StepPolicy).
  virtual void set_policy(const StepPolicy& policy) = 0;
  // One time step (each environment's own dt) of every active environment.
  virtual BatchStepReport step() = 0;
};

}  // namespace grip::solver
