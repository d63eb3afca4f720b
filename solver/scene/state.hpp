#pragma once
// One environment's dynamic state, apart from the shared static Model (MuJoCo's mjData beside
// its mjModel): the DOFs and their velocities, kinematic bodies' poses and scripts, gravity,
// the barrier stiffness and the clock. Everything a step changes lives here.
#include <Eigen/Core>
#include <vector>

#include "solver/scene/scene.hpp"

namespace grip::solver {

struct State {
  Eigen::VectorXd q;        // DOFs: 3 per FEM vertex, 12 per affine body
  Eigen::VectorXd v;        // their velocities
  std::vector<Pose> poses;  // per body; kinematic bodies' current poses (others unused)
  std::vector<Eigen::Vector3d> kinematic_velocity;  // per body, over the last step
  std::vector<Script> scripts;                      // per body
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  std::vector<char> held;  // per DOF: held still by a fixture (Environment::hold); empty: none
  double kappa = 0.0;
  double time = 0.0;
};

}  // namespace grip::solver
