#include "src/trial/hand_trial_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "solver/kernels/affine_body.hpp"
#include "src/geometry/boundary_surface.hpp"
#include "src/metrics/von_mises.hpp"
#include "src/scene/primitives.hpp"

namespace grip::trial {

namespace {

solver::Pose to_pose(const Eigen::Isometry3d& isometry) {
  solver::Pose pose;
  pose.position = isometry.translation();
  pose.rotation = Eigen::Quaterniond(isometry.rotation());
  return pose;
}

// The fingers: one per link hanging from the root link, with every link below it, and each
// link's finger (-1 for the root).
std::vector<HandFinger> find_fingers(const grippers::KinematicTree& tree,
                                     std::vector<int>& link_finger) {
  const auto& links = tree.links();
  const auto& joints = tree.joints();
  std::vector<HandFinger> fingers;
  link_finger.assign(links.size(), -1);
  // Links are numbered depth first from the root (link 0): a link's parent comes before it.
  for (std::size_t l = 1; l < links.size(); ++l) {
    const grippers::KinematicJoint& joint =
        joints.at(static_cast<std::size_t>(links[l].parent_joint));
    if (joint.parent_link == 0) {
      const std::string& name = links[l].name;
      fingers.push_back({name.substr(0, name.find('_')), {}, {}, {}});
      link_finger[l] = static_cast<int>(fingers.size()) - 1;
    } else {
      link_finger[l] = link_finger[static_cast<std::size_t>(joint.parent_link)];
    }
    HandFinger& finger = fingers[static_cast<std::size_t>(link_finger[l])];
    finger.links.push_back(static_cast<int>(l));
    if (joint.dof >= 0) finger.dofs.push_back(joint.dof);
  }
  return fingers;
}

}  // namespace

HandTrialScene::HandTrialScene(const TrialObject& object, grippers::HandModel hand,
                               std::string name, const TrialParameters& parameters)
    : hand_(std::move(hand)), name_(std::move(name)), parameters_(parameters), object_(object) {
  validate(parameters);
  const grippers::KinematicTree& tree = hand_.kinematics;
  fingers_ = find_fingers(tree, link_finger_);
  if (fingers_.empty()) {
    throw std::invalid_argument("hand '" + tree.name() + "' has no fingers (links below its root)");
  }
  for (const grippers::ContactCandidate& c : hand_.points.contacts) {
    contact_link_.push_back(tree.link_index(c.link));
  }

  solver::SceneDescription scene;
  scene.sim = parameters.sim;
  scene.sim.gravity = Eigen::Vector3d::Zero();
  scene.bodies.push_back(object_.description());
  rest_link_poses_ =
      tree.link_poses(Eigen::Isometry3d::Identity(), Eigen::VectorXd::Zero(tree.dof_count()));
  link_body_.assign(tree.links().size(), -1);
  for (std::size_t l = 0; l < tree.links().size(); ++l) {
    const grippers::KinematicLink& link = tree.links()[l];
    if (link.surface.triangles.rows() == 0) continue;
    solver::BodyDescription body;
    body.name = link.name;
    body.vertices = link.surface.vertices;
    body.triangles = link.surface.triangles;
    body.pose = to_pose(rest_link_poses_[l]);
    body.material.friction = parameters.rigid_finger_friction;
    body.collision_group = 0;
    // A finger's links are driven: each follows the pose its joints command through a spring
    // of hand_drive_stiffness inside the step (the drive's compliance); the palm is kinematic.
    if (link_finger_[l] >= 0) {
      body.type = solver::BodyType::kAffine;
      body.drive_stiffness = parameters.hand_drive_stiffness;
    } else {
      body.type = solver::BodyType::kKinematic;
    }
    link_body_[l] = static_cast<int>(scene.bodies.size());
    if (link_finger_[l] >= 0) {
      fingers_[static_cast<std::size_t>(link_finger_[l])].bodies.push_back(link_body_[l]);
    }
    scene.bodies.push_back(std::move(body));

    const auto offset = static_cast<int>(rest_surface_.vertices.rows());
    geometry::SurfaceMesh next;
    next.vertices.resize(offset + link.surface.vertices.rows(), 3);
    next.vertices << rest_surface_.vertices,
        (link.surface.vertices * rest_link_poses_[l].linear().transpose()).rowwise() +
            rest_link_poses_[l].translation().transpose();
    next.triangles.resize(rest_surface_.triangles.rows() + link.surface.triangles.rows(), 3);
    next.triangles << rest_surface_.triangles, (link.surface.triangles.array() + offset).matrix();
    rest_surface_ = std::move(next);
  }

  try {
    model_ = solver::Model::build(scene);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("trial of '" + scene.bodies.front().name + "' with hand '" + name_ +
                                "': " + e.what());
  }
  hand_points_ = std::make_unique<metrics::SurfacePoints>(rest_surface_, parameters.metric_samples,
                                                          parameters.metric_seed);
  object_.bind(model_);
}

HandTrialScene::~HandTrialScene() = default;

void HandTrialScene::check(const HandTrialGrasp& grasp) const {
  const grippers::KinematicTree& tree = hand_.kinematics;
  if (grasp.joints.size() != tree.dof_count()) {
    throw std::out_of_range("hand '" + name_ + "' takes " + std::to_string(tree.dof_count()) +
                            " joint values, not " + std::to_string(grasp.joints.size()));
  }
  if (!tree.within_limits(grasp.joints)) {
    throw std::out_of_range("joint values outside the limits of hand '" + name_ + "'");
  }
  if (grasp.contact_normals.rows() != grasp.contacts.rows()) {
    throw std::out_of_range(std::to_string(grasp.contacts.rows()) + " contacts with " +
                            std::to_string(grasp.contact_normals.rows()) + " normals");
  }
}

void HandTrialScene::place(solver::Environment& environment, const HandTrialGrasp& grasp) const {
  check(grasp);
  const std::vector<Eigen::Isometry3d> poses = kinematics().link_poses(grasp.pose, grasp.joints);
  for (std::size_t l = 0; l < poses.size(); ++l) {
    if (link_body_[l] < 0) continue;
    environment.place(link_body_[l], poses[l] * rest_link_poses_[l].inverse());
    environment.set_script(link_body_[l], solver::Script{});
  }
  environment.set_gravity(Eigen::Vector3d::Zero());
}

Eigen::VectorXd HandTrialScene::closing_direction(const HandTrialGrasp& grasp, int finger) const {
  const grippers::KinematicTree& tree = kinematics();
  const std::vector<Eigen::Isometry3d> poses = tree.link_poses(grasp.pose, grasp.joints);
  struct Push {
    int link;
    Eigen::Vector3d point;      // link frame
    Eigen::Vector3d direction;  // world
  };
  std::vector<Push> pushes;
  // A synthesized contact lies on the contact candidate nearest to it (it was one).
  const auto& candidates = hand_.points.contacts;
  for (Eigen::Index i = 0; i < grasp.contacts.rows(); ++i) {
    const Eigen::Vector3d x = grasp.contacts.row(i).transpose();
    double nearest = std::numeric_limits<double>::infinity();
    int link = -1;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      const auto on = static_cast<std::size_t>(contact_link_[c]);
      const double d = (poses[on] * candidates[c].position - x).norm();
      if (d < nearest) {
        nearest = d;
        link = contact_link_[c];
      }
    }
    if (link >= 0 && link_finger_[static_cast<std::size_t>(link)] == finger) {
      pushes.push_back({link, poses[static_cast<std::size_t>(link)].inverse() * x,
                        -grasp.contact_normals.row(i).transpose().normalized()});
    }
  }
  if (pushes.empty()) {
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      const auto link = static_cast<std::size_t>(contact_link_[c]);
      if (link_finger_[link] != finger) continue;
      pushes.push_back({contact_link_[c], candidates[c].position,
                        poses[link].linear() * candidates[c].normal.normalized()});
    }
  }
  Eigen::VectorXd direction = Eigen::VectorXd::Zero(tree.dof_count());
  std::vector<Eigen::Matrix<double, 3, Eigen::Dynamic>> jacobians;
  for (const Push& push : pushes) {
    jacobians.push_back(tree.point_jacobian(poses, push.link, push.point).topRows<3>());
    direction += jacobians.back().transpose() * push.direction;
  }
  // Only the finger's own joints (a push cannot move the palm or another finger anyway),
  // without round-off (a joint whose axis is square to every push) and without pushing a
  // joint that sits at a limit past it.
  const std::vector<int>& dofs = fingers_.at(static_cast<std::size_t>(finger)).dofs;
  double largest = 0.0;
  for (int dof : dofs) largest = std::max(largest, std::abs(direction[dof]));
  Eigen::VectorXd own = Eigen::VectorXd::Zero(tree.dof_count());
  for (int dof : dofs) {
    const double rate = direction[dof];
    const bool blocked = (rate > 0.0 && grasp.joints[dof] >= tree.upper_limits()[dof]) ||
                         (rate < 0.0 && grasp.joints[dof] <= tree.lower_limits()[dof]);
    if (std::abs(rate) > 1e-9 * largest && !blocked) own[dof] = rate;
  }
  double fastest = 0.0;
  for (const auto& jacobian : jacobians) fastest = std::max(fastest, (jacobian * own).norm());
  if (!(fastest > 1e-12)) return Eigen::VectorXd::Zero(tree.dof_count());
  return own / fastest;
}

Eigen::VectorXd HandTrialScene::finger_joints(const Eigen::VectorXd& start,
                                              const Eigen::VectorXd& direction, int finger,
                                              double travel) const {
  const grippers::KinematicTree& tree = kinematics();
  Eigen::VectorXd joints = start;
  for (int dof : fingers_.at(static_cast<std::size_t>(finger)).dofs) {
    joints[dof] = std::clamp(start[dof] + travel * direction[dof], tree.lower_limits()[dof],
                             tree.upper_limits()[dof]);
  }
  return joints;
}

double HandTrialScene::closing_travel(const Eigen::VectorXd& start,
                                      const Eigen::VectorXd& direction, int finger) const {
  const grippers::KinematicTree& tree = kinematics();
  double travel = std::numeric_limits<double>::infinity();
  for (int dof : fingers_.at(static_cast<std::size_t>(finger)).dofs) {
    if (direction[dof] == 0.0) continue;
    const double limit = direction[dof] > 0.0 ? tree.upper_limits()[dof] : tree.lower_limits()[dof];
    travel = std::min(travel, std::max(0.0, (limit - start[dof]) / direction[dof]));
  }
  return std::isinf(travel) ? 0.0 : travel;
}

void HandTrialScene::move_finger(solver::Environment& environment, const Eigen::Isometry3d& pose,
                                 int finger, const Eigen::VectorXd& joints) const {
  const std::vector<Eigen::Isometry3d> poses = kinematics().link_poses(pose, joints);
  // One keyframe: the pose the link reaches at the end of the step (and holds after it).
  solver::Script script;
  script.keyframes.resize(1);
  script.keyframes[0].time = environment.time() + parameters_.sim.dt;
  for (int link : fingers_.at(static_cast<std::size_t>(finger)).links) {
    const int body = link_body_[static_cast<std::size_t>(link)];
    if (body < 0) continue;
    script.keyframes[0].pose = to_pose(poses[static_cast<std::size_t>(link)]);
    environment.set_script(body, script);
  }
}

void HandTrialScene::place_finger(solver::Environment& environment, const Eigen::Isometry3d& pose,
                                  int finger, const Eigen::VectorXd& from,
                                  const Eigen::VectorXd& to) const {
  const std::vector<Eigen::Isometry3d> now = kinematics().link_poses(pose, from);
  const std::vector<Eigen::Isometry3d> next = kinematics().link_poses(pose, to);
  for (int link : fingers_.at(static_cast<std::size_t>(finger)).links) {
    const auto l = static_cast<std::size_t>(link);
    if (link_body_[l] < 0) continue;
    environment.place(link_body_[l], next[l] * now[l].inverse());
  }
}

void HandTrialScene::hold_finger(solver::Environment& environment, int finger) const {
  for (int body : fingers_.at(static_cast<std::size_t>(finger)).bodies) {
    environment.set_script(body, solver::Script{});
  }
}

geometry::Vertices HandTrialScene::hand_surface_vertices(
    const solver::Environment& environment) const {
  geometry::Vertices vertices(rest_surface_.vertices.rows(), 3);
  Eigen::Index row = 0;
  for (int body : link_body_) {
    if (body < 0) continue;
    const geometry::Vertices link = environment.body_vertices(body);
    vertices.middleRows(row, link.rows()) = link;
    row += link.rows();
  }
  return vertices;
}

metrics::DistanceMetrics HandTrialScene::grasp_distances(
    const solver::Environment& environment) const {
  return object_.distances(environment,
                           hand_points_->positions(hand_surface_vertices(environment)));
}

}  // namespace grip::trial
