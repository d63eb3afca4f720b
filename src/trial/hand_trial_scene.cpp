#include "src/trial/hand_trial_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
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

// Appends the hand's fingers: one per link hanging from the root link, with every link below
// it; sets each link's finger (an index of `fingers`; -1 for the root). `suffix` ends the names.
void find_fingers(const grippers::KinematicTree& tree, int hand, const std::string& suffix,
                  std::vector<HandFinger>& fingers, std::vector<int>& link_finger) {
  const auto& links = tree.links();
  const auto& joints = tree.joints();
  link_finger.assign(links.size(), -1);
  // Links are numbered depth first from the root (link 0): a link's parent comes before it.
  for (std::size_t l = 1; l < links.size(); ++l) {
    const grippers::KinematicJoint& joint =
        joints.at(static_cast<std::size_t>(links[l].parent_joint));
    if (joint.parent_link == 0) {
      const std::string& name = links[l].name;
      fingers.push_back({name.substr(0, name.find('_')) + suffix, hand, {}, {}, {}});
      link_finger[l] = static_cast<int>(fingers.size()) - 1;
    } else {
      link_finger[l] = link_finger[static_cast<std::size_t>(joint.parent_link)];
    }
    HandFinger& finger = fingers[static_cast<std::size_t>(link_finger[l])];
    finger.links.push_back(static_cast<int>(l));
    if (joint.dof >= 0) finger.dofs.push_back(joint.dof);
  }
}

// The meshes a and b as one (b's vertices after a's).
geometry::SurfaceMesh joined(const geometry::SurfaceMesh& a, const geometry::SurfaceMesh& b) {
  const auto offset = static_cast<int>(a.vertices.rows());
  geometry::SurfaceMesh both;
  both.vertices.resize(a.vertices.rows() + b.vertices.rows(), 3);
  both.vertices << a.vertices, b.vertices;
  both.triangles.resize(a.triangles.rows() + b.triangles.rows(), 3);
  both.triangles << a.triangles, (b.triangles.array() + offset).matrix();
  return both;
}

}  // namespace

HandTrialScene::HandTrialScene(const TrialObject& object, grippers::HandModel hand,
                               std::string name, const TrialParameters& parameters)
    : HandTrialScene(
          object,
          [&] {
            std::vector<grippers::HandModel> hands;
            hands.push_back(std::move(hand));
            return hands;
          }(),
          std::move(name), parameters) {}

HandTrialScene::HandTrialScene(const TrialObject& object, std::vector<grippers::HandModel> hands,
                               std::string name, const TrialParameters& parameters)
    : hands_(std::move(hands)), name_(std::move(name)), parameters_(parameters), object_(object) {
  validate(parameters);
  if (hands_.empty() || hands_.size() > 2) {
    throw std::invalid_argument("a trial takes one or two hands, not " +
                                std::to_string(hands_.size()));
  }
  solver::SceneDescription scene;
  scene.sim = parameters.sim;
  scene.sim.gravity = Eigen::Vector3d::Zero();
  scene.bodies.push_back(object_.description(parameters.object_damping));
  std::vector<geometry::SurfaceMesh> hand_surfaces;
  for (std::size_t h = 0; h < hands_.size(); ++h) {
    const grippers::KinematicTree& tree = hands_[h].kinematics;
    const std::string suffix = h == 0 ? std::string() : std::string(" 2");
    HandLinks& links = links_.emplace_back();
    const std::size_t first_finger = fingers_.size();
    find_fingers(tree, static_cast<int>(h), suffix, fingers_, links.finger);
    if (fingers_.size() == first_finger) {
      throw std::invalid_argument("hand '" + tree.name() +
                                  "' has no fingers (links below its root)");
    }
    for (const grippers::ContactCandidate& c : hands_[h].points.contacts) {
      links.contact_link.push_back(tree.link_index(c.link));
    }
    links.rest_poses =
        tree.link_poses(Eigen::Isometry3d::Identity(), Eigen::VectorXd::Zero(tree.dof_count()));
    links.body.assign(tree.links().size(), -1);
    geometry::SurfaceMesh surface;
    for (std::size_t l = 0; l < tree.links().size(); ++l) {
      const grippers::KinematicLink& link = tree.links()[l];
      if (link.surface.triangles.rows() == 0) continue;
      solver::BodyDescription body;
      body.name = link.name + suffix;
      body.vertices = link.surface.vertices;
      body.triangles = link.surface.triangles;
      body.pose = to_pose(links.rest_poses[l]);
      body.material.friction = parameters.rigid_finger_friction;
      body.collision_group = static_cast<int>(h);
      // A finger's links are driven: each follows the pose its joints command through a spring
      // of hand_drive_stiffness inside the step (the drive's compliance); the palm is kinematic.
      if (links.finger[l] >= 0) {
        body.type = solver::BodyType::kAffine;
        body.drive_stiffness = parameters.hand_drive_stiffness;
      } else {
        body.type = solver::BodyType::kKinematic;
      }
      links.body[l] = static_cast<int>(scene.bodies.size());
      if (links.finger[l] >= 0) {
        fingers_[static_cast<std::size_t>(links.finger[l])].bodies.push_back(links.body[l]);
      }
      scene.bodies.push_back(std::move(body));

      geometry::SurfaceMesh posed;
      posed.vertices =
          (link.surface.vertices * links.rest_poses[l].linear().transpose()).rowwise() +
          links.rest_poses[l].translation().transpose();
      posed.triangles = link.surface.triangles;
      surface = joined(surface, posed);
    }
    rest_surface_ = joined(rest_surface_, surface);
    hand_surfaces.push_back(std::move(surface));
  }

  try {
    model_ = solver::Model::build(scene);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("trial of '" + scene.bodies.front().name + "' with hand '" + name_ +
                                "': " + e.what());
  }
  hand_points_ = std::make_unique<metrics::SurfacePoints>(rest_surface_, parameters.metric_samples,
                                                          parameters.metric_seed);
  if (hands_.size() > 1) {
    for (const geometry::SurfaceMesh& surface : hand_surfaces) {
      each_hand_points_.emplace_back(surface, parameters.metric_samples, parameters.metric_seed);
    }
  }
  hand_rest_surfaces_ = std::move(hand_surfaces);
  object_.bind(model_);
}

HandTrialScene::~HandTrialScene() = default;

const HandTrialScene::HandLinks& HandTrialScene::links_of(int finger) const {
  return links_[static_cast<std::size_t>(fingers_.at(static_cast<std::size_t>(finger)).hand)];
}

void HandTrialScene::check(const HandTrialGrasp& grasp, int h) const {
  const grippers::KinematicTree& tree = kinematics(h);
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

void HandTrialScene::place(solver::EnvironmentHandle& environment, const HandTrialGrasp& grasp,
                           int h) const {
  check(grasp, h);
  const HandLinks& links = links_[static_cast<std::size_t>(h)];
  const std::vector<Eigen::Isometry3d> poses = kinematics(h).link_poses(grasp.pose, grasp.joints);
  for (std::size_t l = 0; l < poses.size(); ++l) {
    if (links.body[l] < 0) continue;
    environment.place(links.body[l], poses[l] * links.rest_poses[l].inverse());
    environment.set_script(links.body[l], solver::Script{});
  }
  environment.set_gravity(Eigen::Vector3d::Zero());
}

Eigen::VectorXd HandTrialScene::closing_direction(const HandTrialGrasp& grasp, int finger) const {
  const int h = fingers_.at(static_cast<std::size_t>(finger)).hand;
  const grippers::KinematicTree& tree = kinematics(h);
  const std::vector<int>& contact_link = links_of(finger).contact_link;
  const std::vector<int>& link_finger = links_of(finger).finger;
  const std::vector<Eigen::Isometry3d> poses = tree.link_poses(grasp.pose, grasp.joints);
  struct Push {
    int link;
    Eigen::Vector3d point;      // link frame
    Eigen::Vector3d direction;  // world
  };
  std::vector<Push> pushes;
  // A synthesized contact lies on the contact candidate nearest to it (it was one).
  const auto& candidates = hand(h).points.contacts;
  for (Eigen::Index i = 0; i < grasp.contacts.rows(); ++i) {
    const Eigen::Vector3d x = grasp.contacts.row(i).transpose();
    double nearest = std::numeric_limits<double>::infinity();
    int link = -1;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      const auto on = static_cast<std::size_t>(contact_link[c]);
      const double d = (poses[on] * candidates[c].position - x).norm();
      if (d < nearest) {
        nearest = d;
        link = contact_link[c];
      }
    }
    if (link >= 0 && link_finger[static_cast<std::size_t>(link)] == finger) {
      pushes.push_back({link, poses[static_cast<std::size_t>(link)].inverse() * x,
                        -grasp.contact_normals.row(i).transpose().normalized()});
    }
  }
  if (pushes.empty()) {
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      const auto link = static_cast<std::size_t>(contact_link[c]);
      if (link_finger[link] != finger) continue;
      pushes.push_back({contact_link[c], candidates[c].position,
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
  const grippers::KinematicTree& tree =
      kinematics(fingers_.at(static_cast<std::size_t>(finger)).hand);
  Eigen::VectorXd joints = start;
  for (int dof : fingers_.at(static_cast<std::size_t>(finger)).dofs) {
    joints[dof] = std::clamp(start[dof] + travel * direction[dof], tree.lower_limits()[dof],
                             tree.upper_limits()[dof]);
  }
  return joints;
}

double HandTrialScene::closing_travel(const Eigen::VectorXd& start,
                                      const Eigen::VectorXd& direction, int finger) const {
  const grippers::KinematicTree& tree =
      kinematics(fingers_.at(static_cast<std::size_t>(finger)).hand);
  double travel = std::numeric_limits<double>::infinity();
  for (int dof : fingers_.at(static_cast<std::size_t>(finger)).dofs) {
    if (direction[dof] == 0.0) continue;
    const double limit = direction[dof] > 0.0 ? tree.upper_limits()[dof] : tree.lower_limits()[dof];
    travel = std::min(travel, std::max(0.0, (limit - start[dof]) / direction[dof]));
  }
  return std::isinf(travel) ? 0.0 : travel;
}

void HandTrialScene::move_finger(solver::EnvironmentHandle& environment,
                                 const Eigen::Isometry3d& pose, int finger,
                                 const Eigen::VectorXd& joints) const {
  const HandFinger& f = fingers_.at(static_cast<std::size_t>(finger));
  const std::vector<Eigen::Isometry3d> poses = kinematics(f.hand).link_poses(pose, joints);
  // One keyframe: the pose the link reaches at the end of the step (and holds after it).
  solver::Script script;
  script.keyframes.resize(1);
  script.keyframes[0].time = environment.time() + parameters_.sim.dt;
  for (int link : f.links) {
    const int body = links_of(finger).body[static_cast<std::size_t>(link)];
    if (body < 0) continue;
    script.keyframes[0].pose = to_pose(poses[static_cast<std::size_t>(link)]);
    environment.set_script(body, script);
  }
}

void HandTrialScene::place_finger(solver::EnvironmentHandle& environment,
                                  const Eigen::Isometry3d& pose, int finger,
                                  const Eigen::VectorXd& from, const Eigen::VectorXd& to) const {
  const HandFinger& f = fingers_.at(static_cast<std::size_t>(finger));
  const std::vector<Eigen::Isometry3d> now = kinematics(f.hand).link_poses(pose, from);
  const std::vector<Eigen::Isometry3d> next = kinematics(f.hand).link_poses(pose, to);
  const std::vector<int>& body = links_of(finger).body;
  for (int link : f.links) {
    const auto l = static_cast<std::size_t>(link);
    if (body[l] < 0) continue;
    environment.place(body[l], next[l] * now[l].inverse());
  }
}

void HandTrialScene::hold_finger(solver::EnvironmentHandle& environment, int finger) const {
  for (int body : fingers_.at(static_cast<std::size_t>(finger)).bodies) {
    environment.set_script(body, solver::Script{});
  }
}

geometry::Vertices HandTrialScene::hand_vertices(const solver::EnvironmentHandle& environment,
                                                 int h) const {
  Eigen::Index rows = 0;
  std::vector<geometry::Vertices> links;
  for (int body : links_[static_cast<std::size_t>(h)].body) {
    if (body < 0) continue;
    links.push_back(environment.body_vertices(body));
    rows += links.back().rows();
  }
  geometry::Vertices vertices(rows, 3);
  Eigen::Index row = 0;
  for (const geometry::Vertices& link : links) {
    vertices.middleRows(row, link.rows()) = link;
    row += link.rows();
  }
  return vertices;
}

geometry::Vertices HandTrialScene::surface_vertices(
    const solver::EnvironmentHandle& environment) const {
  if (hands_.size() == 1) return hand_vertices(environment, 0);
  const geometry::Vertices right = hand_vertices(environment, 0);
  const geometry::Vertices left = hand_vertices(environment, 1);
  geometry::Vertices both(right.rows() + left.rows(), 3);
  both << right, left;
  return both;
}

std::vector<BodyVertex> HandTrialScene::surface_sources() const {
  std::vector<BodyVertex> sources;
  for (const HandLinks& links : links_) {
    for (const int body : links.body) {
      if (body < 0) continue;
      const solver::BodyModel& model = model_->bodies()[static_cast<std::size_t>(body)];
      const int count = model.kind->vertex_count(model.local);
      for (int v = 0; v < count; ++v) sources.push_back({body, v});
    }
  }
  return sources;
}

metrics::DistanceMetrics HandTrialScene::grasp_distances(
    const solver::EnvironmentHandle& environment) const {
  return object_.distances(environment, hand_points_->positions(surface_vertices(environment)));
}

std::vector<metrics::DistanceMetrics> HandTrialScene::gripper_distances(
    const solver::EnvironmentHandle& environment) const {
  std::vector<metrics::DistanceMetrics> distances;
  for (std::size_t h = 0; h < each_hand_points_.size(); ++h) {
    distances.push_back(object_.distances(environment, each_hand_points_[h].positions(hand_vertices(
                                                           environment, static_cast<int>(h)))));
  }
  return distances;
}

}  // namespace grip::trial
