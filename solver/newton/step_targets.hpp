#pragma once
// What a step is heading for: the start state, and where bodies without DOFs and pinned vertices
// must be at its end. Prescribed motion is applied progressively (progress 0 -> 1) so that CCD
// can stop it short of a contact and Newton can make room before it goes on.
#include <Eigen/Core>
#include <vector>

#include "solver/model/model.hpp"
#include "solver/scene/state.hpp"

namespace grip::solver {

struct StepTargets {
  Eigen::VectorXd q_start;
  Eigen::VectorXd prescribed_target;  // valid at prescribed DOFs
  Vertices kinematic_start;           // valid at kinematic collision vertices
  Vertices kinematic_target;
  std::vector<Pose> pose_target;  // per body (kinematic: the script's next pose)
};

// The targets of the step of length h from `state` (its scripts advanced by h).
StepTargets step_targets(const Model& model, const State& state, double h);
// Targets of no motion: everything where `state` has it.
StepTargets targets_at_rest(const Model& model, const State& state);

// The collision vertices' positions at DOFs q, with kinematic vertices `progress` of the way
// from their start to their target.
Vertices collision_positions(const Model& model, const Eigen::VectorXd& q,
                             const StepTargets& targets, double progress);

}  // namespace grip::solver
