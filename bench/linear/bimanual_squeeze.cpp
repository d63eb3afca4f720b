#include "bench/linear/bimanual_squeeze.hpp"

#include <cmath>
#include <string>

#include "src/geometry/primitives.hpp"
#include "src/scene/primitives.hpp"

namespace grip::bench {

namespace {

constexpr double kCube = 0.06;                  // m, edge of the squeezed cube
const Eigen::Vector3d kPad(0.015, 0.04, 0.04);  // m, thickness along the squeeze axis
constexpr double kJawThickness = 0.005;         // m
constexpr double kGap = 1.1e-3;                 // m, pad to cube at the start: just beyond d_hat
constexpr double kDuration = 1.0;               // s, the jaws' keyframed closing time

// A pad on the side `sign` (+1 or -1) of `axis`, as a soft body pinned by its outer face to a
// kinematic jaw that closes towards the cube. Adds both bodies to the scene.
void add_finger(solver::SceneDescription& scene, int axis, int sign, double cell,
                double closing_speed) {
  const Eigen::Matrix3d turn =
      axis == 0 ? Eigen::Matrix3d::Identity()
                : Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d out = sign * Eigen::Vector3d::Unit(axis);
  const std::string name = std::string(sign > 0 ? "+" : "-") + (axis == 0 ? "x" : "y");

  solver::BodyDescription pad;
  pad.name = "pad " + name;
  pad.type = solver::BodyType::kFem;
  scene::set_fem_mesh(pad, scene::box_tets(kPad, cell));
  pad.vertices = (pad.vertices * turn.transpose()).eval();  // thickness along `axis`
  pad.pose.position = (kCube / 2 + kGap + kPad.x() / 2) * out;
  pad.material.youngs = 1e6;
  pad.material.poisson = 0.45;

  const geometry::SurfaceMesh jaw_box = geometry::make_box(Eigen::Vector3d(
      axis == 0 ? kJawThickness : kPad.y(), axis == 0 ? kPad.y() : kJawThickness, kPad.z()));
  solver::BodyDescription jaw;
  jaw.name = "jaw " + name;
  jaw.type = solver::BodyType::kKinematic;
  jaw.vertices = jaw_box.vertices;
  jaw.triangles = jaw_box.triangles;
  jaw.pose.position = (kCube / 2 + kGap + kPad.x() + kJawThickness / 2) * out;
  solver::Keyframe start, end;
  start.pose = jaw.pose;
  end.time = kDuration;
  end.pose.position = jaw.pose.position - closing_speed * kDuration * out;
  jaw.script.keyframes = {start, end};

  solver::Pin pin;
  pin.kinematic_body = static_cast<int>(scene.bodies.size()) + 1;
  for (Eigen::Index v = 0; v < pad.vertices.rows(); ++v) {
    if (std::abs(pad.vertices.row(v).dot(out) - kPad.x() / 2) < 1e-9) {
      pin.vertices.push_back(static_cast<int>(v));
    }
  }
  pad.pins = {pin};
  scene.bodies.push_back(pad);
  scene.bodies.push_back(jaw);
}

}  // namespace

solver::SceneDescription bimanual_squeeze(double cell, double closing_speed) {
  solver::SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d::Zero();
  solver::BodyDescription cube;
  cube.name = "cube";
  cube.type = solver::BodyType::kFem;
  scene::set_fem_mesh(cube, scene::box_tets(Eigen::Vector3d::Constant(kCube), cell));
  cube.material.youngs = 1e5;
  cube.material.poisson = 0.4;
  scene.bodies.push_back(cube);
  for (int axis = 0; axis < 2; ++axis) {
    for (int sign : {-1, 1}) add_finger(scene, axis, sign, cell, closing_speed);
  }
  return scene;
}

}  // namespace grip::bench
