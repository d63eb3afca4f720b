#include "src/trial/trial_scene.hpp"

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

TrialScene::TrialScene(const TrialObject& object, const grippers::ParallelGripper& gripper,
                       const TrialParameters& parameters)
    : gripper_(gripper), parameters_(parameters), object_(object) {
  validate(parameters);
  solver::SceneDescription scene;
  scene.sim = parameters.sim;
  scene.sim.gravity = Eigen::Vector3d::Zero();
  scene.bodies.push_back(object_.description());

  geometry::SurfaceMesh finger_mesh;  // both fingers over their body vertices
  for (int j = 0; j < 2; ++j) {
    canonical_[j] = gripper.finger_pose(kJaws[j], gripper.max_opening);
    const solver::Pose pose = to_pose(canonical_[j]);
    solver::BodyDescription finger;
    finger.name = std::string("finger") + kJawSuffix[j];
    finger.pose = pose;
    if (gripper.soft_finger) {
      const grippers::FinRayFinger& soft = *gripper.soft_finger;
      solver::BodyDescription jaw;
      jaw.name = std::string("jaw") + kJawSuffix[j];
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
      jaws_[j].jaw = static_cast<int>(scene.bodies.size());
      scene.bodies.push_back(std::move(jaw));

      finger.type = solver::BodyType::kFem;
      scene::set_fem_mesh(finger, soft.mesh);
      finger.material.density = soft.material.density;
      finger.material.youngs = soft.material.youngs_modulus;
      finger.material.poisson = soft.material.poisson_ratio;
      finger.material.friction = soft.material.friction;
      finger.pins.push_back({jaws_[j].jaw, soft.mount_vertices});
      jaws_[j].finger = static_cast<int>(scene.bodies.size());
    } else {
      finger.type = solver::BodyType::kKinematic;
      finger.vertices = gripper.finger_surface.vertices;
      finger.triangles = gripper.finger_surface.triangles;
      finger.material.friction = parameters.rigid_finger_friction;
      jaws_[j].jaw = jaws_[j].finger = static_cast<int>(scene.bodies.size());
    }
    const int offset = static_cast<int>(finger_mesh.vertices.rows());
    geometry::SurfaceMesh next;
    next.vertices.resize(finger_mesh.vertices.rows() + finger.vertices.rows(), 3);
    next.vertices << finger_mesh.vertices, finger.vertices;
    next.triangles.resize(finger_mesh.triangles.rows() + finger.triangles.rows(), 3);
    next.triangles << finger_mesh.triangles, (finger.triangles.array() + offset).matrix();
    finger_mesh = std::move(next);
    scene.bodies.push_back(std::move(finger));
  }

  // The fin-ray's pads set their contacts' friction themselves (GRIP: mu = 3.5 for the fin-ray
  // gripper, whatever the object); other fingers combine sqrt(mu_object mu_finger), so that the
  // object's own mu matters against rigid jaws and hand links (docs/trial.md, "Friction").
  if (gripper.soft_finger) {
    for (int j = 0; j < 2; ++j) {
      scene.contacts.push_back(
          {object_body(), jaws_[j].finger, gripper.soft_finger->material.friction});
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

  object_.bind(model_);
}

TrialScene::~TrialScene() = default;

void TrialScene::place(solver::Environment& environment, const ParallelGrasp& grasp) const {
  for (int j = 0; j < 2; ++j) {
    const Eigen::Isometry3d motion =
        grasp.pose * gripper_.finger_pose(kJaws[j], grasp.opening) * canonical_[j].inverse();
    environment.place(jaws_[j].jaw, motion);
    if (jaws_[j].finger != jaws_[j].jaw) environment.place(jaws_[j].finger, motion);
    environment.set_script(jaws_[j].jaw, solver::Script{});
  }
  environment.set_gravity(Eigen::Vector3d::Zero());
}

void TrialScene::advance_jaw(solver::Environment& environment, const ParallelGrasp& grasp, int jaw,
                             double distance) const {
  const Eigen::Isometry3d motion(
      Eigen::Translation3d(closing_velocity(grasp, kJaws[jaw], distance)));
  environment.place(jaws_[jaw].jaw, motion);
  if (jaws_[jaw].finger != jaws_[jaw].jaw) environment.place(jaws_[jaw].finger, motion);
}

Eigen::Vector3d TrialScene::closing_velocity(const ParallelGrasp& grasp, grippers::Jaw jaw,
                                             double speed) const {
  const double sign = jaw == Jaw::kPositive ? -1.0 : 1.0;
  return sign * speed * grasp.pose.linear().col(1);
}

geometry::Vertices TrialScene::gripper_surface_vertices(
    const solver::Environment& environment) const {
  const Eigen::Index per_finger = surface_to_body_.size();
  geometry::Vertices vertices(2 * per_finger, 3);
  for (int j = 0; j < 2; ++j) {
    const geometry::Vertices body = environment.body_vertices(jaws_[j].finger);
    for (Eigen::Index v = 0; v < per_finger; ++v) {
      vertices.row(j * per_finger + v) = body.row(surface_to_body_[v]);
    }
  }
  return vertices;
}

int TrialScene::gripper_surface_vertex_count() const {
  return 2 * static_cast<int>(surface_to_body_.size());
}

metrics::DistanceMetrics TrialScene::grasp_distances(const solver::Environment& environment) const {
  return object_.distances(environment, finger_points_->positions(finger_vertices(environment)));
}

Eigen::VectorXd TrialScene::body_stress(const solver::Environment& environment, int body) const {
  if (body == object_body()) return object_.stress(environment);
  if (!gripper_.soft_finger || (body != jaws_[0].finger && body != jaws_[1].finger)) return {};
  const solver::Material& material = model_->bodies()[body].material;
  return metrics::von_mises_stress(gripper_.soft_finger->mesh, environment.body_vertices(body),
                                   material.youngs, material.poisson);
}

geometry::Vertices TrialScene::finger_vertices(const solver::Environment& environment) const {
  const geometry::Vertices a = environment.body_vertices(jaws_[0].finger);
  const geometry::Vertices b = environment.body_vertices(jaws_[1].finger);
  geometry::Vertices both(a.rows() + b.rows(), 3);
  both << a, b;
  return both;
}

}  // namespace grip::trial
