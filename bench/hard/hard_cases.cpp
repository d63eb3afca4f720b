// The hard-case suite of `grip bench hard`: each case a scene built in code, with its steps and
// its physical check (bench/hard/hard_case.hpp says what a case is).
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "bench/hard/hard_case.hpp"
#include "src/geometry/primitives.hpp"
#include "src/scene/primitives.hpp"

namespace grip::bench {
namespace {

using solver::BodyDescription;
using solver::BodyType;
using solver::Environment;
using solver::Keyframe;
using solver::SceneDescription;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDHat = 1e-3;  // the default barrier distance, which every case keeps

Eigen::Quaterniond about(const Eigen::Vector3d& axis, double angle) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized()));
}

BodyDescription kinematic_box(const std::string& name, const Eigen::Vector3d& size,
                              const Eigen::Vector3d& position) {
  return scene::surface_body(name, BodyType::kKinematic, geometry::make_box(size), position);
}

BodyDescription affine_box(const std::string& name, const Eigen::Vector3d& size,
                           const Eigen::Vector3d& position, double density) {
  BodyDescription body =
      scene::surface_body(name, BodyType::kAffine, geometry::make_box(size), position);
  body.material.density = density;
  return body;
}

// A 1 m x 1 m kinematic slab whose top face is the plane z = 0.
BodyDescription ground() { return kinematic_box("ground", {1.0, 1.0, 0.1}, {0.0, 0.0, -0.05}); }

BodyDescription fem_box(const std::string& name, const Eigen::Vector3d& size, double cell,
                        const Eigen::Vector3d& position, double youngs) {
  BodyDescription body;
  body.name = name;
  body.type = BodyType::kFem;
  scene::set_fem_mesh(body, scene::box_tets(size, cell));
  body.pose.position = position;
  body.material.youngs = youngs;
  return body;
}

// Keyframes that move a kinematic body from `from` to `to` over [0, t_end], then hold.
void move_linearly(BodyDescription& body, const Eigen::Vector3d& to, double t_end) {
  solver::Pose end = body.pose;
  end.position = to;
  body.script.keyframes = {Keyframe{0.0, body.pose}, Keyframe{t_end, end}};
}

// A cone with its apex at the origin, opening along +z to a base of `radius` at z = `height`.
geometry::SurfaceMesh cone(double radius, double height, int segments) {
  geometry::SurfaceMesh mesh;
  mesh.vertices.resize(segments + 2, 3);
  mesh.vertices.row(0) << 0.0, 0.0, 0.0;
  mesh.vertices.row(1) << 0.0, 0.0, height;
  for (int i = 0; i < segments; ++i) {
    const double a = 2.0 * kPi * i / segments;
    mesh.vertices.row(2 + i) << radius * std::cos(a), radius * std::sin(a), height;
  }
  mesh.triangles.resize(2 * segments, 3);
  for (int i = 0; i < segments; ++i) {
    const int r0 = 2 + i;
    const int r1 = 2 + (i + 1) % segments;
    mesh.triangles.row(2 * i) << 0, r1, r0;      // side, seen from outside
    mesh.triangles.row(2 * i + 1) << 1, r0, r1;  // base, facing +z
  }
  return mesh;
}

// A box whose faces are meshed badly on purpose: each face is a grid with lines 1e-7 of its
// size from its edges (needle triangles of aspect ratio about 5e6, corner triangles of 5e-15 of
// the face's area) and its interior grid vertices pushed alternately 1e-9 m in and out
// (neighbouring triangles 1e-7 rad from coplanar across the face, tiny folds along its edges).
// Closed and outward, like any body surface.
geometry::SurfaceMesh degenerate_box(const Eigen::Vector3d& size) {
  constexpr double kSliver = 1e-7;
  constexpr double kBump = 1e-9;
  const double grid[] = {0.0, kSliver, 0.5, 1.0 - kSliver, 1.0};
  constexpr int kN = 5;
  std::map<std::tuple<double, double, double>, int> index;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  auto vertex = [&](const Eigen::Vector3d& p) {
    const auto [it, added] = index.try_emplace({p.x(), p.y(), p.z()}, int(vertices.size()));
    if (added) vertices.push_back(p);
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis) {
    for (const double side : {-1.0, 1.0}) {
      const int u = (axis + 1) % 3;
      const int v = (axis + 2) % 3;
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      normal[axis] = side;
      int ids[kN][kN];
      for (int i = 0; i < kN; ++i)
        for (int j = 0; j < kN; ++j) {
          Eigen::Vector3d p;
          p[axis] = side * size[axis] / 2;
          p[u] = (grid[i] - 0.5) * size[u];
          p[v] = (grid[j] - 0.5) * size[v];
          const bool interior = i > 0 && i < kN - 1 && j > 0 && j < kN - 1;
          if (interior) p += ((i + j) % 2 ? kBump : -kBump) * normal;
          ids[i][j] = vertex(p);
        }
      for (int i = 0; i + 1 < kN; ++i)
        for (int j = 0; j + 1 < kN; ++j) {
          for (Eigen::Vector3i t : {Eigen::Vector3i(ids[i][j], ids[i + 1][j], ids[i + 1][j + 1]),
                                    Eigen::Vector3i(ids[i][j], ids[i + 1][j + 1], ids[i][j + 1])}) {
            const Eigen::Vector3d a = vertices[t[0]], b = vertices[t[1]], c = vertices[t[2]];
            if ((b - a).cross(c - a).dot(normal) < 0) std::swap(t[1], t[2]);
            triangles.push_back(t);
          }
        }
    }
  }
  geometry::SurfaceMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i)
    mesh.vertices.row(Eigen::Index(i)) = vertices[i];
  mesh.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t i = 0; i < triangles.size(); ++i)
    mesh.triangles.row(Eigen::Index(i)) = triangles[i];
  return mesh;
}

int body_index(const Environment& env, const std::string& name) {
  const auto& bodies = env.model().bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].name == name) return static_cast<int>(b);
  }
  return -1;
}

// The body's extent along z now (FEM: all its vertices).
double height(const Environment& env, const std::string& name) {
  const solver::Vertices x = env.body_vertices(body_index(env, name));
  return x.col(2).maxCoeff() - x.col(2).minCoeff();
}

std::string fmt(const char* what, double value, const char* relation, double bound) {
  char text[160];
  std::snprintf(text, sizeof text, "%s = %.4g, should be %s %.4g", what, value, relation, bound);
  return text;
}

std::string fmt_range(const char* what, double value, double lo, double hi) {
  char text[160];
  std::snprintf(text, sizeof text, "%s = %.4g, should be in (%.4g, %.4g)", what, value, lo, hi);
  return text;
}

// --- the cases -------------------------------------------------------------------------------

HardCase thin_plate_squeeze() {
  // A 1.5 mm FEM plate, one tet layer, pinched between two 16 mm jaws that close to 0.75 mm
  // apart: its own top and bottom surfaces come within d_hat of each other (self-contact, no
  // vertex between them) while the jaws press.
  constexpr double kThickness = 0.0015;
  SceneDescription s;
  s.sim.gravity.setZero();
  s.bodies.push_back(fem_box("plate", {0.03, 0.03, kThickness}, 0.0075, {0, 0, 0}, 1e6));
  const double jaw_z = kThickness / 2 + 0.5 * kDHat + 0.005;
  const double travel = 0.5 * kDHat + 0.25 * kThickness;
  for (const double side : {1.0, -1.0}) {
    BodyDescription jaw = kinematic_box(side > 0 ? "top_jaw" : "bottom_jaw", {0.016, 0.016, 0.01},
                                        {0, 0, side * jaw_z});
    move_linearly(jaw, {0, 0, side * (jaw_z - travel)}, 0.1);
    s.bodies.push_back(jaw);
  }
  return {"thin_plate_squeeze",
          "1.5 mm one-layer FEM plate pinched to half its thickness",
          s,
          20,
          false,
          [](const Environment& env, bool last) -> std::string {
            if (!last) return {};
            // Thickness under the jaws: the plate's vertices within the jaws' footprint.
            const solver::Vertices x = env.body_vertices(body_index(env, "plate"));
            double lo = 1.0, hi = -1.0;
            for (Eigen::Index v = 0; v < x.rows(); ++v) {
              if (std::abs(x(v, 0)) < 0.007 && std::abs(x(v, 1)) < 0.007) {
                lo = std::min(lo, x(v, 2));
                hi = std::max(hi, x(v, 2));
              }
            }
            return hi - lo < 0.75e-3 ? ""
                                     : fmt("thickness under the jaws (m)", hi - lo, "<", 0.75e-3);
          }};
}

HardCase plate_drop_flat() {
  // A 0.5 mm affine plate falling flat at 10 m/s (0.1 m per step): face-on-face contact whose
  // edge-edge pairs are all exactly parallel.
  SceneDescription s;
  s.bodies.push_back(ground());
  BodyDescription plate = affine_box("plate", {0.05, 0.05, 0.0005}, {0, 0, 0.00025 + 0.002}, 2700);
  plate.velocity = {0, 0, -10};
  s.bodies.push_back(plate);
  return {"plate_drop_flat",
          "0.5 mm affine plate falling flat at 10 m/s onto the ground",
          s,
          30,
          false,
          [](const Environment& env, bool last) -> std::string {
            const int b = body_index(env, "plate");
            const double z = env.center_of_mass(b).z();
            if (!(z > 0.00025)) return fmt("plate centre height (m)", z, ">", 0.00025);
            if (last && !(z < 0.00025 + kDHat)) {
              return fmt("resting plate centre height (m)", z, "<", 0.00025 + kDHat);
            }
            return {};
          }};
}

HardCase fem_plate_drop() {
  // A 1 mm FEM plate (one tet layer, thickness = d_hat) falling flat at 5 m/s.
  SceneDescription s;
  s.bodies.push_back(ground());
  BodyDescription plate = fem_box("plate", {0.04, 0.04, 0.001}, 0.005, {0, 0, 0.0005 + 0.002}, 1e6);
  plate.velocity = {0, 0, -5};
  s.bodies.push_back(plate);
  return {"fem_plate_drop",
          "1 mm one-layer FEM plate (thickness = d_hat) falling flat at 5 m/s",
          s,
          30,
          false,
          [](const Environment& env, bool last) -> std::string {
            if (!last) return {};
            const double v = env.center_of_mass_velocity(body_index(env, "plate")).norm();
            return v < 0.05 ? "" : fmt("plate speed at the end (m/s)", v, "<", 0.05);
          }};
}

HardCase needle_into_soft_block() {
  // A needle (cone of half-angle 1.1 degrees) pressed 3 mm into a soft block: the whole load
  // sits on its tip vertex, then on the edges of its shaft.
  constexpr double kTop = 0.0205;
  SceneDescription s;
  s.bodies.push_back(ground());
  s.bodies.push_back(fem_box("block", {0.02, 0.02, 0.02}, 0.004, {0, 0, 0.0105}, 1e5));
  BodyDescription needle = scene::surface_body(
      "needle", BodyType::kKinematic, cone(0.0003, 0.015, 12), {0.0011, 0.0007, kTop + 0.001});
  move_linearly(needle, {0.0011, 0.0007, kTop - 0.003}, 0.2);
  s.bodies.push_back(needle);
  return {"needle_into_soft_block",
          "needle tip (1.1 deg half-angle) pressed 3 mm into E = 1e5 Pa",
          s,
          30,
          false,
          [=](const Environment& env, bool last) -> std::string {
            if (!last) return {};
            // The dent: how far the block's top surface went down under the tip.
            const int b = body_index(env, "block");
            const solver::Vertices x = env.body_vertices(b);
            const solver::BodyModel& body = env.model().bodies()[b];
            const solver::Vertices rest = body.kind->rest_vertices(body.local);
            double lowest = kTop;
            for (Eigen::Index v = 0; v < x.rows(); ++v) {
              if (rest(v, 2) > kTop - 1e-9) lowest = std::min(lowest, x(v, 2));
            }
            return kTop - lowest > 0.002 ? "" : fmt("dent depth (m)", kTop - lowest, ">", 0.002);
          }};
}

HardCase box_on_cone_tip() {
  // A rigid box dropped off-centre onto an upward cone tip: point contact on a face, then it
  // tips and slides down the cone onto the ground.
  SceneDescription s;
  s.bodies.push_back(ground());
  BodyDescription tip =
      scene::surface_body("cone", BodyType::kKinematic, cone(0.004, 0.015, 16), {0, 0, 0.015});
  tip.pose.rotation = about(Eigen::Vector3d::UnitX(), kPi);  // apex up at z = 15 mm
  s.bodies.push_back(tip);
  s.bodies.push_back(
      affine_box("box", {0.02, 0.02, 0.02}, {0.003, 0.002, 0.015 + 0.01 + 0.0005}, 500));
  return {"box_on_cone_tip",
          "affine box dropped off-centre onto a cone tip",
          s,
          40,
          false,
          [](const Environment& env, bool last) -> std::string {
            if (!last) return {};
            // Off the tip and at rest on the ground, on one of its faces.
            const double z = env.center_of_mass(body_index(env, "box")).z();
            return z > 0.01 && z < 0.01 + kDHat
                       ? ""
                       : fmt_range("box centre height at the end (m)", z, 0.01, 0.01 + kDHat);
          }};
}

HardCase fast_bullet_thin_wall() {
  // A spinning 5 mm steel cube at 30 m/s (0.3 m per step, 60 cube sizes) against a 0.5 mm wall.
  SceneDescription s;
  s.sim.gravity.setZero();
  s.bodies.push_back(kinematic_box("wall", {0.1, 0.1, 0.0005}, {0, 0, 0}));
  BodyDescription bullet = affine_box("bullet", {0.005, 0.005, 0.005}, {0, 0, 0.02}, 8000);
  bullet.velocity = {0, 0, -30};
  bullet.angular_velocity = {20, 30, 0};
  s.bodies.push_back(bullet);
  return {"fast_bullet_thin_wall",
          "spinning 5 mm cube at 30 m/s into a 0.5 mm wall (CCD)",
          s,
          10,
          false,
          [](const Environment& env, bool) -> std::string {
            const double z = env.center_of_mass(body_index(env, "bullet")).z();
            return z > 0.00025 ? "" : fmt("bullet centre height (m)", z, ">", 0.00025);
          }};
}

HardCase stiffness_ratio() {
  // Soft (E = 1e5 Pa) on stiff (E = 1e9 Pa) FEM, pressed by a plate: 1e4 between the bodies'
  // stiffnesses in one Newton system.
  SceneDescription s;
  s.bodies.push_back(ground());
  s.bodies.push_back(fem_box("stiff", {0.03, 0.03, 0.01}, 0.005, {0, 0, 0.0055}, 1e9));
  s.bodies.push_back(fem_box("soft", {0.02, 0.02, 0.02}, 0.005, {0, 0, 0.021}, 1e5));
  BodyDescription plate = kinematic_box("plate", {0.05, 0.05, 0.01}, {0, 0, 0.0365});
  move_linearly(plate, {0, 0, 0.0365 - 0.0035}, 0.1);
  s.bodies.push_back(plate);
  return {"stiffness_ratio_1e4",
          "soft FEM (1e5 Pa) pressed onto stiff FEM (1e9 Pa)",
          s,
          20,
          false,
          [](const Environment& env, bool last) -> std::string {
            if (!last) return {};
            const double soft = height(env, "soft");
            if (!(soft < 0.018)) return fmt("soft block height (m)", soft, "<", 0.018);
            const double stiff = height(env, "stiff");
            return stiff > 0.01 - 1e-6 ? ""
                                       : fmt("stiff block height (m)", stiff, ">", 0.01 - 1e-6);
          }};
}

HardCase mass_ratio() {
  // A 0.27 kg box resting on a 0.26 g box: 1e3 between the masses.
  SceneDescription s;
  s.bodies.push_back(ground());
  s.bodies.push_back(affine_box("light", {0.04, 0.04, 0.02}, {0, 0, 0.0105}, 8));
  s.bodies.push_back(
      affine_box("heavy", {0.03, 0.03, 0.03}, {0, 0, 0.021 + 0.0005 + 0.015}, 10000));
  return {"mass_ratio_1e3",
          "0.27 kg box resting on a 0.26 g box",
          s,
          50,
          false,
          [](const Environment& env, bool last) -> std::string {
            if (!last) return {};
            const double gap = env.center_of_mass(body_index(env, "heavy")).z() -
                               env.center_of_mass(body_index(env, "light")).z() - 0.025;
            if (!(gap > 0 && gap < kDHat))
              return fmt_range("gap between the boxes (m)", gap, 0.0, kDHat);
            const double v = env.center_of_mass_velocity(body_index(env, "heavy")).norm();
            return v < 0.01 ? "" : fmt("heavy box speed at the end (m/s)", v, "<", 0.01);
          }};
}

HardCase friction_incline() {
  // mu = 3.5 holds a box on a 70 degree ramp (tan 70 = 2.75): static friction at 79% of its
  // limit. Smoothed friction lets it creep at most eps_v; it must not slide. The box is flat
  // (6 cm along the slope, 1 cm high) so that it does not topple, as a cube would past 45 deg.
  constexpr double kAngle = 70.0 * kPi / 180.0;
  const Eigen::Vector3d normal(std::sin(kAngle), 0, std::cos(kAngle));
  const Eigen::Vector3d down_slope(std::cos(kAngle), 0, -std::sin(kAngle));
  const Eigen::Quaterniond tilt = about(Eigen::Vector3d::UnitY(), kAngle);
  SceneDescription s;
  BodyDescription ramp = kinematic_box("ramp", {0.3, 0.1, 0.02}, -0.01 * normal);
  ramp.pose.rotation = tilt;
  s.bodies.push_back(ramp);
  // It starts where its weight's barrier force holds it (a start deeper within d_hat would
  // launch it off the ramp with the barrier's stored energy).
  const Eigen::Vector3d start = (0.005 + 0.998 * kDHat) * normal;
  BodyDescription box = affine_box("box", {0.06, 0.04, 0.01}, start, 500);
  box.pose.rotation = tilt;
  s.bodies.push_back(box);
  s.contacts.push_back({0, 1, 3.5});
  return {"mu_3.5_incline",
          "mu = 3.5 holds a box on a 70 degree ramp",
          s,
          50,
          false,
          [=](const Environment& env, bool) -> std::string {
            const double slide = (env.center_of_mass(1) - start).dot(down_slope);
            return slide < 1e-3 ? "" : fmt("slide down the ramp (m)", slide, "<", 1e-3);
          }};
}

HardCase friction_topple() {
  // A cube on the same 70 degree ramp with mu = 3.5 cannot slide but topples (past 45 degrees
  // its weight falls outside its base) and tumbles down: sticking contacts that turn into
  // rolling and lift-off, and the most Newton iterations per step of the suite.
  constexpr double kAngle = 70.0 * kPi / 180.0;
  const Eigen::Vector3d normal(std::sin(kAngle), 0, std::cos(kAngle));
  const Eigen::Quaterniond tilt = about(Eigen::Vector3d::UnitY(), kAngle);
  SceneDescription s;
  BodyDescription ramp = kinematic_box("ramp", {0.3, 0.1, 0.02}, -0.01 * normal);
  ramp.pose.rotation = tilt;
  s.bodies.push_back(ramp);
  BodyDescription box = affine_box("cube", {0.04, 0.04, 0.04}, (0.02 + 0.5 * kDHat) * normal, 500);
  box.pose.rotation = tilt;
  s.bodies.push_back(box);
  s.contacts.push_back({0, 1, 3.5});
  return {"mu_3.5_topple",
          "cube toppling down a 70 degree ramp, mu = 3.5",
          s,
          25,
          false,
          [=](const Environment& env, bool last) -> std::string {
            if (!last) return {};
            const double turned =
                Eigen::AngleAxisd(env.rotation(1) * tilt.toRotationMatrix().transpose()).angle();
            return turned > kPi / 4
                       ? ""
                       : fmt("cube's rotation from its start (rad)", turned, ">", kPi / 4);
          }};
}

HardCase friction_squeeze() {
  // A soft cube held against gravity by two jaws with mu = 3.5: stiff lagged friction on a
  // body that is deforming under the squeeze.
  SceneDescription s;
  s.bodies.push_back(fem_box("cube", {0.02, 0.02, 0.02}, 0.005, {0, 0, 0}, 1e5));
  const double jaw_x = 0.01 + 0.2 * kDHat + 0.005;
  for (const double side : {-1.0, 1.0}) {
    BodyDescription jaw = kinematic_box(side < 0 ? "left_jaw" : "right_jaw", {0.01, 0.04, 0.04},
                                        {side * jaw_x, 0, 0});
    move_linearly(jaw, {side * (jaw_x - 0.0012), 0, 0}, 0.02);
    s.bodies.push_back(jaw);
  }
  s.contacts.push_back({0, 1, 3.5});
  s.contacts.push_back({0, 2, 3.5});
  return {"mu_3.5_squeeze",
          "soft cube held against gravity between jaws, mu = 3.5",
          s,
          40,
          false,
          [](const Environment& env, bool) -> std::string {
            const double drop = -env.center_of_mass(0).z();
            return drop < 1e-3 ? "" : fmt("drop of the held cube (m)", drop, "<", 1e-3);
          }};
}

HardCase large_squeeze() {
  // A soft cube flattened to 40% of its height between plates (their gap closes to 10 mm, the
  // barrier keeps about d_hat on each side): large strains, bulging sideways under friction.
  SceneDescription s;
  s.sim.gravity.setZero();
  BodyDescription cube = fem_box("cube", {0.02, 0.02, 0.02}, 0.004, {0, 0, 0}, 1e5);
  cube.material.poisson = 0.45;
  s.bodies.push_back(cube);
  const double plate_z = 0.01 + 0.5 * kDHat + 0.005;
  const double travel = 0.5 * kDHat + 0.005;  // to a 10 mm gap
  for (const double side : {1.0, -1.0}) {
    BodyDescription plate =
        kinematic_box(side > 0 ? "top" : "bottom", {0.1, 0.1, 0.01}, {0, 0, side * plate_z});
    move_linearly(plate, {0, 0, side * (plate_z - travel)}, 0.3);
    s.bodies.push_back(plate);
  }
  return {"large_squeeze",
          "soft cube flattened to 40% of its height",
          s,
          40,
          false,
          [](const Environment& env, bool last) -> std::string {
            if (!last) return {};
            const double ratio = height(env, "cube") / 0.02;
            return ratio < 0.45 ? "" : fmt("height / initial height", ratio, "<", 0.45);
          }};
}

HardCase parallel_edge_edge() {
  // A box balanced edge-down on a ridge, the two edges 1e-4 rad from parallel: the edge-edge
  // distance is ill-conditioned and the mollifier is active along the whole contact line.
  const double half_diagonal = 0.01 * std::sqrt(2.0);
  SceneDescription s;
  BodyDescription floor = ground();
  floor.pose.position.z() -= half_diagonal + 0.001;
  s.bodies.push_back(floor);
  BodyDescription ridge = kinematic_box("ridge", {0.1, 0.02, 0.02}, {0, 0, 0});
  ridge.pose.rotation = about(Eigen::Vector3d::UnitX(), kPi / 4);
  s.bodies.push_back(ridge);
  BodyDescription box =
      affine_box("box", {0.1, 0.02, 0.02}, {0, 0, 2 * half_diagonal + 0.5 * kDHat}, 1000);
  box.pose.rotation =
      about(Eigen::Vector3d::UnitZ(), 1e-4) * about(Eigen::Vector3d::UnitX(), kPi / 4);
  s.bodies.push_back(box);
  return {"parallel_edge_edge",
          "box edge on a ridge edge, 1e-4 rad from parallel",
          s,
          30,
          false,
          [=](const Environment& env, bool) -> std::string {
            // Balanced (the scene is symmetric): the edge-edge contact alone carries its weight.
            const double gap = env.center_of_mass(body_index(env, "box")).z() - 2 * half_diagonal;
            return gap > 0 && gap < kDHat ? ""
                                          : fmt_range("gap between the edges (m)", gap, 0.0, kDHat);
          }};
}

HardCase start_within_d_hat() {
  // Three bodies starting 0.1 d_hat from the ground and from each other: barriers active at
  // the first iteration, at 2e2 times their force at 0.5 d_hat.
  constexpr double kGap = 0.1 * kDHat;
  SceneDescription s;
  s.bodies.push_back(ground());
  s.bodies.push_back(affine_box("base", {0.02, 0.02, 0.02}, {0, 0, 0.01 + kGap}, 1000));
  s.bodies.push_back(affine_box("beside", {0.02, 0.02, 0.02}, {0.02 + kGap, 0, 0.01 + kGap}, 1000));
  s.bodies.push_back(fem_box("top", {0.02, 0.02, 0.02}, 0.01, {0, 0, 0.03 + 2 * kGap}, 1e6));
  return {"start_within_d_hat", "three bodies starting 0.1 d_hat apart", s, 20, false, {}};
}

HardCase degenerate_meshes() {
  // Needle and near-zero-area triangles and nearly coplanar faces, on a tilted falling box, a
  // box resting flat, and the slab they land on.
  SceneDescription s;
  s.bodies.push_back(scene::surface_body("slab", BodyType::kKinematic,
                                         degenerate_box({0.2, 0.2, 0.02}), {0, 0, -0.01}));
  BodyDescription falling = scene::surface_body(
      "falling", BodyType::kAffine, degenerate_box({0.02, 0.02, 0.02}), {0.03, 0, 0.018});
  falling.pose.rotation =
      about(Eigen::Vector3d::UnitX(), 0.1) * about(Eigen::Vector3d::UnitY(), 0.05);
  s.bodies.push_back(falling);
  s.bodies.push_back(scene::surface_body("resting", BodyType::kAffine,
                                         degenerate_box({0.02, 0.02, 0.02}), {-0.03, 0, 0.0105}));
  return {"degenerate_meshes",
          "sliver, near-zero-area and nearly coplanar triangles",
          s,
          40,
          false,
          [](const Environment& env, bool last) -> std::string {
            if (!last) return {};
            // Both boxes end at rest on a face, within d_hat of the slab.
            for (const char* name : {"falling", "resting"}) {
              const double z = env.center_of_mass(body_index(env, name)).z();
              if (!(z > 0.01 && z < 0.01 + kDHat))
                return fmt_range("box centre height at the end (m)", z, 0.01, 0.01 + kDHat);
            }
            return {};
          }};
}

HardCase impossible_push() {
  // A soft cube pinned by its back face to a jaw that drives it into a fixed wall and beyond:
  // no intersection-free state exists once the pinned face reaches the wall, so the solver must
  // stop with a reason rather than accept a step.
  SceneDescription s;
  s.sim.gravity.setZero();
  s.bodies.push_back(kinematic_box("wall", {0.01, 0.05, 0.05}, {0.0105 + 0.005, 0, 0}));
  BodyDescription jaw = kinematic_box("jaw", {0.01, 0.03, 0.03}, {-0.01, 0, 0});
  jaw.script.velocity = {0.1, 0, 0};
  s.bodies.push_back(jaw);
  BodyDescription cube = fem_box("cube", {0.01, 0.01, 0.01}, 0.005, {0, 0, 0}, 1e5);
  solver::Pin pin{1, {}};
  for (Eigen::Index v = 0; v < cube.vertices.rows(); ++v) {
    if (cube.vertices(v, 0) < -0.005 + 1e-9) pin.vertices.push_back(static_cast<int>(v));
  }
  cube.pins.push_back(pin);
  s.bodies.push_back(cube);
  return {"impossible_push",
          "pinned soft cube driven through a wall: the solver must refuse",
          s,
          20,
          true,
          {}};
}

}  // namespace

std::vector<HardCase> hard_cases() {
  return {
      thin_plate_squeeze(), plate_drop_flat(),       fem_plate_drop(),    needle_into_soft_block(),
      box_on_cone_tip(),    fast_bullet_thin_wall(), stiffness_ratio(),   mass_ratio(),
      friction_incline(),   friction_topple(),       friction_squeeze(),  large_squeeze(),
      parallel_edge_edge(), start_within_d_hat(),    degenerate_meshes(), impossible_push()};
}

}  // namespace grip::bench
