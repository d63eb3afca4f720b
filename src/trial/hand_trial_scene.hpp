#pragma once
// The trial scene of a dexterous hand (the LEAP-style hand), or two (bimanual: a right and a left
// hand): the solver scene in hand-canonical placement
// (object at the world origin, each hand frame = world, joints at 0) with one body per link, its
// Model, the hands' fingers, how a candidate places a hand and how a finger's joints move it.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "solver/engine/engine.hpp"
#include "solver/model/model.hpp"
#include "src/geometry/mesh.hpp"
#include "src/geometry/signed_distance.hpp"
#include "src/grippers/hand_model.hpp"
#include "src/metrics/distance_metrics.hpp"
#include "src/metrics/surface_points.hpp"
#include "src/synth/candidate.hpp"
#include "src/trial/object_body.hpp"
#include "src/trial/trial_object.hpp"
#include "src/trial/trial_parameters.hpp"
#include "src/trial/trial_scene.hpp"

namespace grip::trial {

// One hand candidate (a synthesized candidate's hand): world from hand frame, the joint values
// (rad, the hand's degrees of freedom in order) and the synthesized contacts (world points on the
// hand's fingers and the object's outward normals there; may be empty). The contacts steer how
// the fingers close.
using HandTrialGrasp = synth::HandGrasp;

// A finger: a subtree of links hanging from the palm (the root link) of one hand, named by its
// first link's name up to the first '_' ("index_knuckle": "index"; the second hand's fingers
// are suffixed " 2").
struct HandFinger {
  std::string name;
  int hand = 0;             // the hand it belongs to
  std::vector<int> links;   // its hand's kinematic tree links
  std::vector<int> bodies;  // their solver bodies (links with a surface)
  std::vector<int> dofs;    // its hand's degrees of freedom that move it
};

class HandTrialScene final : public TrialScene {
 public:
  // Builds the scene and its Model: the object (one affine body, or FEM when soft) and one
  // kinematic body per link with a surface (friction `rigid_finger_friction`). `name` is the
  // gripper's dataset name (e.g. "leap"). Throws std::invalid_argument (naming the object) for
  // an unusable object or parameters, or a hand without fingers.
  HandTrialScene(const TrialObject& object, grippers::HandModel hand, std::string name,
                 const TrialParameters& parameters);
  // The same with one or two hands (bimanual: the right hand first, then the left). Each hand's
  // links are one collision group (they do not touch each other; the other hand's they do).
  // The first hand's bodies come first, as with one hand; the second's names are suffixed " 2".
  HandTrialScene(const TrialObject& object, std::vector<grippers::HandModel> hands,
                 std::string name, const TrialParameters& parameters);
  ~HandTrialScene() override;
  HandTrialScene(const HandTrialScene&) = delete;
  HandTrialScene& operator=(const HandTrialScene&) = delete;

  const std::shared_ptr<const solver::Model>& model() const override { return model_; }
  const TrialParameters& parameters() const override { return parameters_; }
  int gripper_count() const override { return hand_count(); }
  // Kind "hand", its joints in degree-of-freedom order (rad), its fingers, every link at joints 0
  // in the hand frame (hand_rest_surface). A right and a left hand: hands = 2, named
  // "NAME-bimanual", joint and finger names per hand (the left hand's are the right's), then the
  // right hand's surface and the left one's, each in its own hand frame. Throws
  // std::invalid_argument for two hands that differ in joints, fingers or surface size.
  io::GripperRecord gripper_record() const override;
  std::string description() const override;
  // Each candidate's hands: a pose, the joint values and the synthesized contacts, which steer
  // how each finger closes.
  std::unique_ptr<TrialGripper> protocol_gripper(
      const std::vector<synth::Candidate>& candidates) const override;

  int hand_count() const { return static_cast<int>(hands_.size()); }
  const grippers::HandModel& hand(int h = 0) const {
    return hands_.at(static_cast<std::size_t>(h));
  }
  const grippers::KinematicTree& kinematics(int h = 0) const { return hand(h).kinematics; }
  const std::string& name() const { return name_; }
  bool soft_object() const { return object_.soft(); }
  int object_body() const { return 0; }

  // Every hand's fingers, hand by hand.
  const std::vector<HandFinger>& fingers() const { return fingers_; }

  // Throws std::out_of_range unless the grasp has one joint value per degree of freedom of hand
  // h, within the limits, and as many contact normals as contacts.
  void check(const HandTrialGrasp& grasp, int h = 0) const;

  // Moves hand h's links of a fresh environment to the candidate's pose and joints
  // (Environment::place), holds them still and turns gravity off. Throws as check() does.
  void place(solver::EnvironmentHandle& environment, const HandTrialGrasp& grasp, int h = 0) const;

  // The finger's closing direction in its hand's joint space at `grasp`, its hand's candidate
  // (zero outside its degrees of freedom), scaled so that its fastest pushed point moves 1 m per
  // unit: the joint velocity J^T d summed over the points it pushes, each point p along d. Those
  // are the candidate's contacts on this finger, pushed into the object (d = -normal), as
  // DexGraspNet's evaluation does; a finger without one pushes its contact candidates (the hand
  // points) along their own outward normals, i.e. the way its pad faces. A joint already at a limit
  // is not pushed past it. Zero when the finger cannot move so.
  Eigen::VectorXd closing_direction(const HandTrialGrasp& grasp, int finger) const;

  // The finger's joints at `travel` along `direction` from `start` (clamped to the limits), and
  // the travel at which the first of them reaches its limit (0 for a zero direction).
  Eigen::VectorXd finger_joints(const Eigen::VectorXd& start, const Eigen::VectorXd& direction,
                                int finger, double travel) const;
  double closing_travel(const Eigen::VectorXd& start, const Eigen::VectorXd& direction,
                        int finger) const;

  // Scripts the finger's links to reach joint values `joints` (only the finger's own are read)
  // at the end of the next step, or holds them where they are.
  void move_finger(solver::EnvironmentHandle& environment, const Eigen::Isometry3d& pose,
                   int finger, const Eigen::VectorXd& joints) const;
  void hold_finger(solver::EnvironmentHandle& environment, int finger) const;
  // Before the first step: moves the finger's links from where joint values `from` put them to
  // where `to` does.
  void place_finger(solver::EnvironmentHandle& environment, const Eigen::Isometry3d& pose,
                    int finger, const Eigen::VectorXd& from, const Eigen::VectorXd& to) const;

  // The hand's surface: every link with a surface in link order, each link's vertices in its
  // mesh's order (hand after hand). rest_surface() has the joints at 0 in the hand frame (the
  // dataset's gripper surface); surface_vertices() is the same vertices in an environment
  // now.
  const geometry::SurfaceMesh& rest_surface() const { return rest_surface_; }
  // Hand h's rows of rest_surface(), in its own hand frame (the left hand mirrors the right).
  const geometry::SurfaceMesh& hand_rest_surface(int h) const {
    return hand_rest_surfaces_.at(static_cast<std::size_t>(h));
  }
  geometry::Vertices surface_vertices(const solver::EnvironmentHandle& environment) const;
  std::vector<BodyVertex> surface_sources() const;

  // The object's pose as a row-major 3x4 [A | t], world from object frame (A: the affine
  // body's matrix; a soft object's best-fit rotation).
  std::array<double, 12> object_pose(const solver::EnvironmentHandle& environment) const {
    return object_.pose(environment);
  }

  // D1/D2 now: the object's signed distance (its current surface) at the D1/D2 points, which
  // are sampled once on the rest surface of the hands' links and follow them; and per hand, from
  // points sampled on its own links (empty for one hand).
  metrics::DistanceMetrics grasp_distances(const solver::EnvironmentHandle& environment) const;
  std::vector<metrics::DistanceMetrics> gripper_distances(
      const solver::EnvironmentHandle& environment) const;

  // Von Mises stress per tet of one body now (Pa); empty for a body that is not FEM.
  Eigen::VectorXd body_stress(const solver::EnvironmentHandle& environment, int body) const {
    return body == object_body() ? object_.stress(environment) : Eigen::VectorXd();
  }

 private:
  // One hand's links: per link its body, finger and rest pose; its contact candidates' links.
  struct HandLinks {
    std::vector<int> body;          // its body, -1 without a surface
    std::vector<int> finger;        // its finger (an index of fingers_), -1 for the palm
    std::vector<int> contact_link;  // per contact candidate (hand points): its link
    std::vector<Eigen::Isometry3d> rest_poses;  // joints at 0, hand frame = world
  };

  const HandLinks& links_of(int finger) const;
  // Hand h's surface vertices now, the rows of surface_vertices() it takes.
  geometry::Vertices hand_vertices(const solver::EnvironmentHandle& environment, int h) const;

  std::vector<grippers::HandModel> hands_;
  std::string name_;
  TrialParameters parameters_;
  ObjectBody object_;  // body 0
  std::vector<HandFinger> fingers_;
  std::vector<HandLinks> links_;
  geometry::SurfaceMesh rest_surface_;
  std::vector<geometry::SurfaceMesh> hand_rest_surfaces_;
  std::shared_ptr<const solver::Model> model_;
  std::unique_ptr<metrics::SurfacePoints> hand_points_;
  std::vector<metrics::SurfacePoints> each_hand_points_;  // when there are two
};

}  // namespace grip::trial
