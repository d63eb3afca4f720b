#pragma once
// The scene `grip bench model` compares models on: a cube squeezed between two parallel finger
// pads (gravity off while they close, each until its force on the cube reaches a stop force, as
// in the grasp trial), then held against gravity. Each part can be modelled
// lean (affine object, kinematic fingers) or in full (stiff FEM stand-ins), with the same
// collision surfaces either way, so that two variants differ only in what they simulate.
#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "solver/environment.hpp"
#include "solver/model/model.hpp"

namespace grip::bench {

struct SqueezeOptions {
  bool fem_object = false;   // the cube as a stiff FEM body instead of one affine body
  bool fem_fingers = false;  // pads as stiff FEM bodies pinned by their back face to kinematic
                             // jaw blocks (as the fin-ray finger is), instead of kinematic pads
  bool ground = false;       // a kinematic floor just under the cube
  double friction = 0.5;     // mu of every body, so of every pair (sqrt(mu_a mu_b))
  // Pa, of the FEM stand-ins for rigid parts: at 1e8 Pa the cube still yields microns under
  // 10 N, as much as the barrier does, and the closing force stops 20% lower.
  double stiff_youngs = 1e9;
  double object_size = 0.04;  // m, cube edge
  double object_cell = 0.01;  // m, tet cell of the cube (its surface is the affine cube's too)
  // m, tet cell of the pads (their surface is the kinematic pads' too). Their grid must not line
  // up with the cube's: edges of two aligned grids meet parallel, in degenerate contacts that
  // Newton converges on badly.
  double pad_cell = 0.0125;
  // m, between each pad and the cube at the start: just beyond d_hat (1 mm), so that the pads
  // squeeze from the second step on, at a speed the stiff barrier allows: 1 um per step (at
  // kappa = 3e6 N/m, 5 um inside d_hat is some 10 N over a face; 0.1 mm, some 100 N per contact).
  double gap = 1.002e-3;
  double closing_speed = 1e-4;  // m/s per pad
  double stop_force = 10.0;     // N, normal force on the cube that stops a pad
  int max_closing_steps = 40;   // gravity off, pads closing (at most)
  int hold_steps = 20;          // gravity on (-z), pads still
};

// Bodies: 0 the cube, 1 and 2 the pads (+x, -x), then the jaw blocks (FEM pads), then the floor.
struct SqueezeScene {
  std::shared_ptr<const solver::Model> model;
  int pads[2] = {1, 2};
  Eigen::VectorXi object_surface;  // the cube's surface vertices among its body vertices
};

SqueezeScene make_squeeze_scene(const SqueezeOptions& options);

// What one run of the scene ended with.
struct SqueezeResult {
  bool failed = false;
  std::string failure;
  int free_dofs = 0;  // DOFs solved for (pinned ones left out)
  long newton_iterations = 0;
  double wall_s = 0.0;              // the steps alone (not building the model)
  double cpu_s = 0.0;               // the process's CPU time over the same steps
  solver::Vertices object_surface;  // world positions, in the order of the cube's surface
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // the cube's centre of mass
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  double closing_force = 0.0;  // N, mean over the pads of the normal force on the cube
  int friction_contacts = 0;   // lagged friction contacts of the last step
  Eigen::VectorXd dofs;        // the final state, for bit-for-bit comparisons
};

// Freezes the end state of `environment` (the cube's pose and surface, the closing force).
SqueezeResult squeeze_result(const SqueezeScene& scene, const solver::Environment& environment);

// Where one environment stands in the protocol.
struct SqueezeProgress {
  bool stopped[2] = {false, false};
  int steps = 0;  // taken so far
  int held = 0;   // of them, under gravity
};

// The pads' normal force on the cube after the last step (N), per pad.
double pad_force(const SqueezeScene& scene, const solver::Environment& environment, int pad);

// Sets gravity and the pads' scripts for the environment's next step: gravity off and each pad
// closing until it has stopped (or closing has taken max_closing_steps), then gravity on and the
// pads still. False once the protocol is over (no step to take).
bool next_squeeze_step(const SqueezeOptions& options, const SqueezeScene& scene,
                       solver::Environment& environment, SqueezeProgress& progress);

// Runs the whole protocol in one environment; `place` (if given) moves the cube first.
// `friction_terms_at_zero_mu` forces friction terms on pairs with mu = 0.
SqueezeResult run_squeeze(const SqueezeOptions& options, const SqueezeScene& scene,
                          const Eigen::Isometry3d& place = Eigen::Isometry3d::Identity(),
                          bool friction_terms_at_zero_mu = false);

// The lean result's distance from the full one's: the cube's centre of mass (m), its rotation
// (rad), the largest distance between matching surface vertices (m) and the closing force
// (relative).
struct SqueezeError {
  double center_m = 0.0;
  double rotation_rad = 0.0;
  double vertex_m = 0.0;
  double force_relative = 0.0;
};
SqueezeError squeeze_error(const SqueezeResult& lean, const SqueezeResult& full);

}  // namespace grip::bench
