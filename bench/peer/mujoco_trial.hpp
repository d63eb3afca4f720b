#pragma once
// The grasp trial of a parallel gripper on a rigid object run in MuJoCo (an optional
// dependency: mujoco_available() says whether this build has it): the same jaws, object mesh,
// grip force and six-axis gravity test as grip's protocol, and grip's verdict rule. Rigid jaws
// are boxes; soft (fin-ray) fingers are MuJoCo flexes of the same tets and material.
#include <array>
#include <string>

#include <Eigen/Geometry>

#include "src/geometry/mesh.hpp"
#include "src/grippers/parallel_gripper.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::bench {

// Whether this build has MuJoCo, and its version ("2.2.2"; empty without it).
bool mujoco_available();
std::string mujoco_version();

// MuJoCo's own settings of the peer trial; the protocol's lengths and forces are grip's.
struct MujocoSettings {
  double timestep = 0.001;  // s
  // Contacts as stiff as MuJoCo recommends: their time constant two steps (default 0.02 s), and
  // their impedance (solimp d0 = dwidth; default 0.9 to 0.95). MuJoCo's contacts are soft
  // constraints: under a force F they sink about (1 - d) / d F tc^2 / m_eff, with m_eff the
  // bodies' reduced mass along the normal, so light objects sink most.
  double contact_time_constant = 0.005;  // s
  double contact_impedance = 0.99;
  double jaw_mass = 0.1;        // kg, gravity compensated
  double closing_margin = 1.0;  // s allowed beyond the jaws' travel at squeeze_speed
  // Soft fingers (flexes), where MuJoCo's defaults do not hold (docs/results.md, the peer
  // section): a flex's degrees of freedom are a trilinear field over this many cells of its
  // bounding box (finger frame x, y, z: four along the length, so that it bends), not one point
  // per tet vertex (its per-vertex "full" dofs let the jaws push the fingers through the object
  // and its effective-metric solve does not converge; "quadratic" went unstable at first
  // contact). The contacts are stiffer than the rigid jaws' (their vertices are light, so a
  // contact of the same time constant sinks deeper), which needs a shorter step.
  std::array<int, 3> flex_cells = {1, 1, 4};
  double flex_timestep = 0.0005;              // s
  double flex_contact_time_constant = 0.001;  // s
  double flex_contact_impedance = 0.9999;
  // A soft finger comes to its grip force as the damped jaw compresses it, with a time constant
  // of its damping over the finger's stiffness (about 0.8 s for the fin-ray): more time to rest.
  double flex_closing_margin = 4.0;  // s
  // MuJoCo's experimental IPC contact mode (<flag ipc>, discrete integrator): it solves the
  // contacts of 2D flexes with static geoms or other flexes, frictionless; 3D flexes against a
  // moving object keep their constraint rows. For soft fingers only.
  bool ipc = false;
  // The hand (mujoco_hand_trial.hpp): each link's mass (its weight cancelled); each joint's
  // position servo gain, the rotor inertia it drives (armature) and its damping, near critical
  // (2 sqrt(kp armature)); a finger's speed along its path before it first touches the object.
  double link_mass = 0.05;         // kg
  double joint_stiffness = 300.0;  // N m/rad
  double joint_armature = 0.005;   // kg m^2
  double joint_damping = 2.5;      // N m s/rad
  double approach_speed = 0.05;    // m/s
};

struct MujocoOutcome {
  // "success", or grip's failure kinds: no_contact, lost_contact, displaced, unsettled,
  // numerical (MuJoCo's instability warning); "load_error" if the model did not compile.
  std::string verdict;
  std::string message;  // MuJoCo's error or warning, if any
  bool settled = false;
  std::array<double, 2> closing_forces = {0.0, 0.0};  // N per jaw when settled
  double largest_slip = 0.0;                          // m, as grip's verdict measures it
  // At the settled grasp (where the trial ended if it did not settle): world from finger frame,
  // world from object frame and the soft fingers' tet vertices in the world.
  std::array<Eigen::Isometry3d, 2> fingers;
  Eigen::Isometry3d object = Eigen::Isometry3d::Identity();
  std::array<geometry::Vertices, 2> finger_vertices;
  // Where the trial ended (after the gravity phases, or where it stopped): world from object
  // frame, the jaws' poses and the soft fingers' tet vertices.
  Eigen::Isometry3d final_object = Eigen::Isometry3d::Identity();
  std::array<Eigen::Isometry3d, 2> final_fingers;
  std::array<geometry::Vertices, 2> final_finger_vertices;
  // At any step: MuJoCo's deepest contact between the object and a finger (m; its contacts are
  // soft and sink in), and the most of the soft fingers' tets inverted at once.
  double deepest_penetration = 0.0;
  int most_inverted_tets = 0;
  double cpu_seconds = 0.0;          // the process's CPU time for the simulation
  double compile_cpu_seconds = 0.0;  // and for building the model (the mesh's convex hull)
};

// One trial: `object` (closed, outward, object frame = world at the start) of `density` and
// `friction` (combined with the jaws' as grip combines them), the gripper at `pose` (world from
// gripper frame) with its jaws `opening` apart. Without MuJoCo: verdict "load_error".
MujocoOutcome run_mujoco_trial(const geometry::SurfaceMesh& object, double density, double friction,
                               const grippers::ParallelGripper& gripper,
                               const Eigen::Isometry3d& pose, double opening,
                               const trial::TrialParameters& parameters,
                               const MujocoSettings& settings = {});

}  // namespace grip::bench
