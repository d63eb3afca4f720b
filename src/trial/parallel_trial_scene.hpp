#pragma once
// The trial scene of a parallel gripper, or two of one kind (bimanual): the solver scene in
// gripper-canonical placement (object at the world origin, each gripper's frame = world, jaws at
// the widest opening), its Model, which body plays which role, and how one candidate places each
// gripper in an environment of that Model.
#include <array>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "solver/engine/engine.hpp"
#include "solver/model/model.hpp"
#include "src/geometry/mesh.hpp"
#include "src/geometry/signed_distance.hpp"
#include "src/grippers/parallel_gripper.hpp"
#include "src/metrics/distance_metrics.hpp"
#include "src/metrics/surface_points.hpp"
#include "src/synth/candidate.hpp"
#include "src/trial/object_body.hpp"
#include "src/trial/trial_object.hpp"
#include "src/trial/trial_parameters.hpp"
#include "src/trial/trial_scene.hpp"

namespace grip::trial {

// One candidate of a parallel gripper: world from gripper frame, and the jaw opening (m).
struct ParallelGrasp {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  double opening = 0.0;
};

// A candidate of one parallel gripper, or of two (bimanual, the first gripper's grasp first):
// each grasp's pose, its opening the gripper's one joint value.
synth::Candidate parallel_candidate(const std::vector<ParallelGrasp>& grasps);

// Body roles per jaw: gripper by gripper, each in grippers::Jaw order (kPositive, kNegative).
struct JawBodies {
  int jaw = -1;     // the kinematic body that moves (rigid: the finger itself)
  int finger = -1;  // the body whose contact force with the object stops the jaw
};

class ParallelTrialScene final : public TrialScene {
 public:
  // Builds the scene and its Model. Soft fingers are FEM bodies pinned by their mount
  // vertices to a kinematic jaw block behind the mount; rigid fingers are kinematic.
  // `grippers` copies of the gripper (1, or 2 for a bimanual trial); the first copy's bodies
  // come first, named as one gripper's ("finger+"), the second's suffixed " 2".
  // Throws std::invalid_argument (naming the object) for an unusable object or parameters.
  ParallelTrialScene(const TrialObject& object, const grippers::ParallelGripper& gripper,
                     const TrialParameters& parameters, int grippers = 1);
  ~ParallelTrialScene() override;
  ParallelTrialScene(const ParallelTrialScene&) = delete;
  ParallelTrialScene& operator=(const ParallelTrialScene&) = delete;

  const std::shared_ptr<const solver::Model>& model() const override { return model_; }
  const TrialParameters& parameters() const override { return parameters_; }
  int gripper_count() const override { return static_cast<int>(jaws_.size()) / 2; }
  // Kind "parallel", one joint ("opening", m), fingers "positive" and "negative" (grippers::Jaw),
  // both fingers at the widest opening in the gripper frame. Two grippers: hands = 2, named
  // "NAME-bimanual", joint and finger names per gripper, the surface once per gripper (each in
  // its own frame).
  io::GripperRecord gripper_record() const override;
  std::string description() const override;
  // Each candidate's hands: a pose and one joint value, the opening (m).
  std::unique_ptr<TrialGripper> protocol_gripper(
      const std::vector<synth::Candidate>& candidates) const override;

  const grippers::ParallelGripper& gripper() const { return gripper_; }
  bool soft_object() const { return object_.soft(); }
  int object_body() const { return 0; }
  // 2 per gripper: jaws()[2 g + j] is jaw j of gripper g.
  const std::vector<JawBodies>& jaws() const { return jaws_; }

  // Moves gripper g's bodies of a fresh environment to the candidate's pose and opening
  // (Environment::place), holds its jaws still and turns gravity off. Throws std::out_of_range
  // for an opening outside the gripper's range.
  void place(solver::EnvironmentHandle& environment, const ParallelGrasp& grasp, int g = 0) const;
  // Before the first step: moves one jaw (an index of jaws()) and its finger `distance` m
  // further along its closing path (negative: back); `grasp` is its gripper's.
  void advance_jaw(solver::EnvironmentHandle& environment, const ParallelGrasp& grasp, int jaw,
                   double distance) const;

  // World velocity of a jaw closing at `speed` (m/s) along the candidate's closing axis.
  Eigen::Vector3d closing_velocity(const ParallelGrasp& grasp, grippers::Jaw jaw,
                                   double speed) const;

  // The grippers' surface vertices in the dataset's order (per gripper gripper.surface():
  // positive finger, then negative), gathered from the environment's finger bodies.
  geometry::Vertices surface_vertices(const solver::EnvironmentHandle& environment) const;
  std::vector<BodyVertex> surface_sources() const;
  int gripper_surface_vertex_count() const;

  // The object's pose as a row-major 3x4 [A | t], world from object frame (A: the affine
  // body's matrix; a soft object's best-fit rotation).
  std::array<double, 12> object_pose(const solver::EnvironmentHandle& environment) const {
    return object_.pose(environment);
  }

  // D1/D2 now: the object's signed distance (its current surface) at the D1/D2 points, which
  // are sampled once on the fingers' rest surfaces (every gripper's) and follow the fingers;
  // and per gripper, from points sampled on its own fingers (empty for one gripper).
  metrics::DistanceMetrics grasp_distances(const solver::EnvironmentHandle& environment) const;
  std::vector<metrics::DistanceMetrics> gripper_distances(
      const solver::EnvironmentHandle& environment) const;

  // Von Mises stress per tet of one body now (Pa); empty for a body that is not FEM.
  Eigen::VectorXd body_stress(const solver::EnvironmentHandle& environment, int body) const;
  // Every soft finger's, gripper after gripper, kPositive's first (the gripper record's order);
  // empty for rigid fingers.
  Eigen::VectorXd finger_stress(const solver::EnvironmentHandle& environment) const;

 private:
  // The fingers' body vertices of grippers [first, last), in jaws() order.
  geometry::Vertices finger_vertices(const solver::EnvironmentHandle& environment, int first,
                                     int last) const;

  grippers::ParallelGripper gripper_;
  TrialParameters parameters_;
  ObjectBody object_;  // body 0
  std::vector<JawBodies> jaws_;
  std::array<Eigen::Isometry3d, 2> canonical_;    // finger frames at the widest opening
  Eigen::VectorXi surface_to_body_;               // finger_surface vertex -> finger body vertex
  std::array<geometry::TetMesh, 2> finger_tets_;  // a soft finger's rest tets, per Jaw
  std::shared_ptr<const solver::Model> model_;
  std::unique_ptr<metrics::SurfacePoints> finger_points_;
  // On one gripper's fingers (every gripper's rest surface is the same), when there are two.
  std::unique_ptr<metrics::SurfacePoints> gripper_points_;
};

}  // namespace grip::trial
