#include "src/trial/parallel_trial_scene.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "solver/kernels/affine_body.hpp"
#include "src/geometry/boundary_surface.hpp"
#include "src/geometry/primitives.hpp"
#include "src/metrics/von_mises.hpp"
#include "src/scene/primitives.hpp"

namespace grip::trial {

namespace {

using grippers::Jaw;
constexpr std::array<Jaw, 2> kJaws = {Jaw::kPositive, Jaw::kNegative};
constexpr std::array<const char*, 2> kJawSuffix = {"+", "-"};

// Depth of the kinematic block behind a soft finger's mount face (the jaw it is clamped in).
constexpr double kJawBlockDepth = 0.010;

solver::Pose to_pose(const Eigen::Isometry3d& isometry) {
  solver::Pose pose;
  pose.position = isometry.translation();
  pose.rotation = Eigen::Quaterniond(isometry.rotation());
  return pose;
}

}  // namespace

ParallelTrialScene::ParallelTrialScene(const TrialObject& object,
                                       const grippers::ParallelGripper& gripper,
                                       const TrialParameters& parameters, int grippers)
    : gripper_(gripper), parameters_(parameters), object_(object) {
  validate(parameters);
  if (grippers < 1 || grippers > 2) {
    throw std::invalid_argument("a trial takes one or two grippers, not " +
                                std::to_string(grippers));
  }
  jaws_.resize(2 * static_cast<std::size_t>(grippers));
  solver::SceneDescription scene;
  scene.sim = parameters.sim;
  scene.sim.gravity = Eigen::Vector3d::Zero();
  scene.bodies.push_back(object_.description(parameters.object_damping));

  geometry::SurfaceMesh finger_mesh;  // every finger over its body vertices
  geometry::SurfaceMesh one_gripper;  // the first gripper's two fingers
  for (std::size_t i = 0; i < jaws_.size(); ++i) {
    const std::size_t j = i % 2;
    const std::string suffix = std::string(kJawSuffix[j]) + (i < 2 ? "" : " 2");
    canonical_[j] = gripper.finger_pose(kJaws[j], gripper.max_opening);
    const solver::Pose pose = to_pose(canonical_[j]);
    solver::BodyDescription finger;
    finger.name = "finger" + suffix;
    finger.pose = pose;
    if (gripper.soft_finger) {
      const grippers::FinRayFinger soft = *gripper.soft_finger_of(kJaws[j]);
      finger_tets_[j] = soft.mesh;
      solver::BodyDescription jaw;
      jaw.name = "jaw" + suffix;
      jaw.type = solver::BodyType::kKinematic;
      jaw.pose = pose;
      const Eigen::Vector3d lower = soft.mesh.vertices.colwise().minCoeff();
      const Eigen::Vector3d upper = soft.mesh.vertices.colwise().maxCoeff();
      geometry::SurfaceMesh block = geometry::make_box(
          Eigen::Vector3d(upper.x() - lower.x(), upper.y() - lower.y(), kJawBlockDepth));
      block.vertices.col(0).array() += 0.5 * (upper.x() + lower.x());
      block.vertices.col(1).array() += 0.5 * (upper.y() + lower.y());
      block.vertices.col(2).array() += lower.z() - 0.5 * kJawBlockDepth;
      jaw.vertices = block.vertices;
      jaw.triangles = block.triangles;
      jaws_[i].jaw = static_cast<int>(scene.bodies.size());
      scene.bodies.push_back(std::move(jaw));

      finger.type = solver::BodyType::kFem;
      scene::set_fem_mesh(finger, soft.mesh);
      finger.material.density = soft.material.density;
      finger.material.youngs = soft.material.youngs_modulus;
      finger.material.poisson = soft.material.poisson_ratio;
      finger.material.friction = soft.material.friction;
      finger.material.damping = soft.material.damping;
      finger.pins.push_back({jaws_[i].jaw, soft.mount_vertices});
      jaws_[i].finger = static_cast<int>(scene.bodies.size());
    } else {
      finger.type = solver::BodyType::kKinematic;
      const geometry::SurfaceMesh surface = gripper.finger_surface_of(kJaws[j]);
      finger.vertices = surface.vertices;
      finger.triangles = surface.triangles;
      finger.material.friction = parameters.rigid_finger_friction;
      jaws_[i].jaw = jaws_[i].finger = static_cast<int>(scene.bodies.size());
    }
    const int offset = static_cast<int>(finger_mesh.vertices.rows());
    geometry::SurfaceMesh next;
    next.vertices.resize(finger_mesh.vertices.rows() + finger.vertices.rows(), 3);
    next.vertices << finger_mesh.vertices, finger.vertices;
    next.triangles.resize(finger_mesh.triangles.rows() + finger.triangles.rows(), 3);
    next.triangles << finger_mesh.triangles, (finger.triangles.array() + offset).matrix();
    finger_mesh = std::move(next);
    if (i == 1) one_gripper = finger_mesh;
    scene.bodies.push_back(std::move(finger));
  }

  // The fin-ray's pads set their contacts' friction themselves (GRIP: mu = 3.5 for the fin-ray
  // gripper, whatever the object); other fingers combine sqrt(mu_object mu_finger), so that the
  // object's own mu matters against rigid jaws and hand links (docs/trial.md, "Friction").
  if (gripper.soft_finger) {
    for (const JawBodies& jaw : jaws_) {
      scene.contacts.push_back({object_body(), jaw.finger, gripper.soft_finger->material.friction});
    }
  }

  if (gripper.soft_finger) {
    geometry::boundary_surface(gripper.soft_finger->mesh, &surface_to_body_);
  } else {
    surface_to_body_ = Eigen::VectorXi::LinSpaced(gripper.finger_surface.vertices.rows(), 0,
                                                  gripper.finger_surface.vertices.rows() - 1);
  }
  try {
    model_ = solver::Model::build(scene);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("trial of '" + scene.bodies.front().name + "' with gripper '" +
                                gripper.name + "': " + e.what());
  }
  finger_points_ = std::make_unique<metrics::SurfacePoints>(finger_mesh, parameters.metric_samples,
                                                            parameters.metric_seed);
  if (grippers > 1) {
    gripper_points_ = std::make_unique<metrics::SurfacePoints>(
        one_gripper, parameters.metric_samples, parameters.metric_seed);
  }

  object_.bind(model_);
}

ParallelTrialScene::~ParallelTrialScene() = default;

void ParallelTrialScene::place(solver::EnvironmentHandle& environment, const ParallelGrasp& grasp,
                               int g) const {
  for (int j = 0; j < 2; ++j) {
    const JawBodies& bodies = jaws_.at(static_cast<std::size_t>(2 * g + j));
    const Eigen::Isometry3d motion =
        grasp.pose * gripper_.finger_pose(kJaws[j], grasp.opening) * canonical_[j].inverse();
    environment.place(bodies.jaw, motion);
    if (bodies.finger != bodies.jaw) environment.place(bodies.finger, motion);
    environment.set_script(bodies.jaw, solver::Script{});
  }
  environment.set_gravity(Eigen::Vector3d::Zero());
}

void ParallelTrialScene::advance_jaw(solver::EnvironmentHandle& environment,
                                     const ParallelGrasp& grasp, int jaw, double distance) const {
  const Eigen::Isometry3d motion(
      Eigen::Translation3d(closing_velocity(grasp, kJaws[jaw % 2], distance)));
  const JawBodies& bodies = jaws_.at(static_cast<std::size_t>(jaw));
  environment.place(bodies.jaw, motion);
  if (bodies.finger != bodies.jaw) environment.place(bodies.finger, motion);
}

Eigen::Vector3d ParallelTrialScene::closing_velocity(const ParallelGrasp& grasp, grippers::Jaw jaw,
                                                     double speed) const {
  const double sign = jaw == Jaw::kPositive ? -1.0 : 1.0;
  return sign * speed * grasp.pose.linear().col(1);
}

geometry::Vertices ParallelTrialScene::surface_vertices(
    const solver::EnvironmentHandle& environment) const {
  const Eigen::Index per_finger = surface_to_body_.size();
  geometry::Vertices vertices(static_cast<Eigen::Index>(jaws_.size()) * per_finger, 3);
  for (Eigen::Index j = 0; j < static_cast<Eigen::Index>(jaws_.size()); ++j) {
    const geometry::Vertices body = environment.body_vertices(jaws_[j].finger);
    for (Eigen::Index v = 0; v < per_finger; ++v) {
      vertices.row(j * per_finger + v) = body.row(surface_to_body_[v]);
    }
  }
  return vertices;
}

std::vector<BodyVertex> ParallelTrialScene::surface_sources() const {
  std::vector<BodyVertex> sources;
  for (const JawBodies& jaw : jaws_) {
    for (const int vertex : surface_to_body_) sources.push_back({jaw.finger, vertex});
  }
  return sources;
}

int ParallelTrialScene::gripper_surface_vertex_count() const {
  return static_cast<int>(jaws_.size() * surface_to_body_.size());
}

metrics::DistanceMetrics ParallelTrialScene::grasp_distances(
    const solver::EnvironmentHandle& environment) const {
  return object_.distances(
      environment, finger_points_->positions(finger_vertices(environment, 0, gripper_count())));
}

std::vector<metrics::DistanceMetrics> ParallelTrialScene::gripper_distances(
    const solver::EnvironmentHandle& environment) const {
  std::vector<metrics::DistanceMetrics> distances;
  if (!gripper_points_) return distances;
  for (int g = 0; g < gripper_count(); ++g) {
    distances.push_back(object_.distances(
        environment, gripper_points_->positions(finger_vertices(environment, g, g + 1))));
  }
  return distances;
}

Eigen::VectorXd ParallelTrialScene::body_stress(const solver::EnvironmentHandle& environment,
                                                int body) const {
  if (body == object_body()) return object_.stress(environment);
  const auto jaw = std::find_if(jaws_.begin(), jaws_.end(),
                                [&](const JawBodies& bodies) { return bodies.finger == body; });
  if (!gripper_.soft_finger || jaw == jaws_.end()) return {};
  const solver::Material& material = model_->bodies()[body].material;
  return metrics::von_mises_stress(finger_tets_[static_cast<std::size_t>(jaw - jaws_.begin()) % 2],
                                   environment.body_vertices(body), material.youngs,
                                   material.poisson);
}

Eigen::VectorXd ParallelTrialScene::finger_stress(
    const solver::EnvironmentHandle& environment) const {
  if (!gripper_.soft_finger) return {};
  std::vector<Eigen::VectorXd> fingers;
  Eigen::Index total = 0;
  for (const JawBodies& jaw : jaws_) {
    fingers.push_back(body_stress(environment, jaw.finger));
    total += fingers.back().size();
  }
  Eigen::VectorXd stress(total);
  Eigen::Index at = 0;
  for (const Eigen::VectorXd& finger : fingers) {
    stress.segment(at, finger.size()) = finger;
    at += finger.size();
  }
  return stress;
}

geometry::Vertices ParallelTrialScene::finger_vertices(const solver::EnvironmentHandle& environment,
                                                       int first, int last) const {
  std::vector<geometry::Vertices> bodies;
  Eigen::Index rows = 0;
  for (int i = 2 * first; i < 2 * last; ++i) {
    bodies.push_back(environment.body_vertices(jaws_[static_cast<std::size_t>(i)].finger));
    rows += bodies.back().rows();
  }
  geometry::Vertices all(rows, 3);
  Eigen::Index row = 0;
  for (const geometry::Vertices& v : bodies) {
    all.middleRows(row, v.rows()) = v;
    row += v.rows();
  }
  return all;
}

}  // namespace grip::trial
