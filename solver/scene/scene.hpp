#pragma once
// What the solver is asked to simulate: bodies with their meshes, materials and motion, and
// the simulation parameters. Plain data, filled by a scene file reader or by the grasp trial;
// the solver reads no files.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace grip::solver {

using Vertices = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Tetrahedra = Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor>;

// kinematic: follows a script, has no degrees of freedom (gripper links, jaws, the ground).
// affine: a stiff body with 12 DOFs (ABD). fem: a soft tetrahedral body, 3 DOFs per vertex.
enum class BodyType { kKinematic, kAffine, kFem };

struct Pose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
};

struct Keyframe {
  double time = 0.0;
  Pose pose;
};

// How a kinematic body moves. Without keyframes: constant linear and angular velocity (world
// frame, about the body frame's origin). With keyframes: positions interpolated linearly and
// rotations by slerp between them, held before the first and after the last.
struct Script {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  std::vector<Keyframe> keyframes;
};

struct Material {
  double density = 1000.0;  // kg/m^3
  double youngs = 1e6;      // Pa (FEM)
  double poisson = 0.4;     // (FEM)
  double friction = 0.5;    // mu, combined per pair (see ContactOverride)
  // FEM: Rayleigh stiffness-proportional damping beta (s), the viscous force -beta K v of a
  // material that dissipates as it deforms; 0, none (docs/simulation.md, "Damping").
  double damping = 0.0;
};

// FEM vertices rigidly attached to a kinematic body: they follow it exactly (a soft finger's
// mount on a moving jaw). A pinned body never collides with the body it is pinned to.
struct Pin {
  int kinematic_body = -1;
  std::vector<int> vertices;
};

struct BodyDescription {
  std::string name;
  BodyType type = BodyType::kAffine;
  Vertices vertices;    // in the body frame, metres
  Triangles triangles;  // closed, outward boundary surface (of the tet mesh for FEM)
  Tetrahedra tets;      // FEM only, positively oriented
  Pose pose;            // where the body frame starts
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // initial, of the centre of mass
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // initial, rad/s, world frame
  Script script;                                               // kinematic only
  Material material;
  double orthogonality_stiffness = 1e9;  // affine only, Pa (docs/simulation.md says why)
  std::vector<Pin> pins;                 // FEM only
  // Affine only; > 0 makes the body driven (N/m): a spring inside the step pulls it towards the
  // pose its script gives (translation at this stiffness, rotation in proportion to the body's
  // mass distribution), as a position-controlled drive with compliance would, and gravity does
  // not act on it (the drive carries its weight). A trial's hand links.
  double drive_stiffness = 0.0;
  // Bodies of one group (>= 0) never touch each other: the links of one hand, which overlap at
  // their joints.
  int collision_group = -1;
};

// The friction coefficient of one pair of bodies, overriding the default combination
// mu = sqrt(mu_a mu_b) of their materials.
struct ContactOverride {
  int body_a = -1;
  int body_b = -1;
  double friction = 0.0;
};

struct SimParameters {
  double dt = 0.01;                                        // s
  Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.81);  // m/s^2
  double d_hat = 1e-3;                                     // m, barrier activation distance
  double kappa = 3e6;                                      // N/m, barrier stiffness
  bool adaptive_kappa = false;        // start at kappa, double it when contacts come too close
  double eps_v = 1e-3;                // m/s, static-to-dynamic friction transition
  double newton_tol = 1e-3;           // relative: residual against its first value (or the weight)
  double newton_velocity_tol = 1e-6;  // m/s: a Newton step changing no velocity more is done
  int max_newton_iters = 100;
  // Newton iterations of a solve with every contact Hessian projected to PSD; after these, the
  // exact ones (projected only where their sum is not positive definite). Projection makes a
  // contact stiffer than it is in the modes a compressive load softens: a rigid box squeezed
  // face to face between jaws converges only linearly with it (0.98 per iteration), and the
  // exact Hessians restore Newton's quadratic rate. The first iterations keep projection, the
  // more robust far from the solution (bench/hard: a box landing on a cone's tip).
  int projected_iterations = 10;
  // A step that fails is rolled back and retried as two steps of half its length, at most this
  // many halvings deep (dt / 2^k), before the environment fails.
  int max_step_halvings = 3;
  int friction_lag_iterations = 1;
  // A positive-definite (projected) Newton system is first solved by CG preconditioned with the
  // last factorization, an earlier iteration's or step's, to a relative residual of
  // reuse_tolerance within reuse_iterations iterations, and factorized afresh only if that fails
  // (docs/simulation.md, item 3); 0 iterations factorizes every system.
  int reuse_iterations = 10;
  double reuse_tolerance = 1e-3;
  double ccd_rescaling = 0.1;  // ACCD's s: keep at least s of each gap per line search
};

struct SceneDescription {
  std::vector<BodyDescription> bodies;
  std::vector<ContactOverride> contacts;
  SimParameters sim;
};

}  // namespace grip::solver
