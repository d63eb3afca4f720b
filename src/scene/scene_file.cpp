#include "src/scene/scene_file.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "solver/body/body_registry.hpp"
#include "solver/model/model.hpp"
#include "src/config/config.hpp"
#include "src/config/parameter_table.hpp"
#include "src/geometry/boundary_surface.hpp"
#include "src/geometry/mesh_io.hpp"
#include "src/geometry/mesh_measures.hpp"
#include "src/geometry/primitives.hpp"
#include "src/geometry/tet_mesh_io.hpp"
#include "src/geometry/tetrahedralize.hpp"
#include "src/scene/primitives.hpp"
#include "src/scene/sim_parameters.hpp"

namespace grip::scene {
namespace {

using config::Table;

Eigen::Vector3d vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

std::string number_text(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

// Extrinsic XYZ Euler angles in degrees: about world x, then world y, then world z.
Eigen::Quaterniond rotation_from_degrees(const Eigen::Vector3d& degrees) {
  const Eigen::Vector3d r = degrees * std::numbers::pi / 180.0;
  return Eigen::AngleAxisd(r.z(), Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(r.y(), Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(r.x(), Eigen::Vector3d::UnitX());
}

double positive(const Table& table, std::string_view key, double fallback) {
  const double value = table.number_or(key, fallback);
  if (!(value > 0)) table.fail(key, "must be positive");
  return value;
}

void read_sim(const Table& sim, SceneFile& out) {
  sim.allow(config::parameter_keys(sim_parameter_table()), {"duration", "gravity"});
  solver::SimParameters& p = out.scene.sim;
  read_sim_parameters(sim, p);
  out.duration = positive(sim, "duration", out.duration);
  p.gravity = vec(sim.vec3_or("gravity", {p.gravity.x(), p.gravity.y(), p.gravity.z()}));
  // Checked in floating point: a tiny dt or a huge duration must not overflow the count.
  const double steps = std::round(out.duration / p.dt);
  const std::string_view key = sim.has("duration") ? "duration" : "dt";
  const std::string given =
      "(duration " + number_text("%g", out.duration) + " s, dt " + number_text("%g", p.dt) + " s)";
  if (!(steps >= 1)) {
    sim.fail(key, "makes no step " + given + "; make duration at least dt");
  }
  if (!(steps <= static_cast<double>(kMaxSceneSteps))) {
    sim.fail(key, "makes " + number_text("%.3g", steps) + " steps " + given + ", more than the " +
                      std::to_string(kMaxSceneSteps) +
                      " a scene may run; shorten duration or raise dt");
  }
}

// Refuses an FEM resolution that would make more than `max_tets` tets (by default the limit of
// `grip asset prepare`), before the mesh is built.
void check_tet_count(const Table& body, double resolution, double tets, double max_tets) {
  if (tets <= max_tets) return;
  body.fail("resolution", "= " + number_text("%g", resolution) + " m would make about " +
                              number_text("%.3g", tets) + " tets, more than the " +
                              number_text("%.0f", max_tets) +
                              " allowed; use a larger resolution (a coarser mesh)");
}

// A body from a tet mesh file (another tool's volume mesh), used as it is: an FEM body's tets,
// or a rigid body's boundary.
void read_tet_mesh_shape(const Table& body, const std::filesystem::path& scene_dir, double max_tets,
                         bool soft, solver::BodyDescription& out) {
  if (body.has("resolution")) {
    body.fail("resolution",
              "does not apply to a tet mesh file, which is simulated as it is; "
              "remove it (or give a surface mesh to be meshed at a resolution)");
  }
  std::filesystem::path file = body.string("file");
  if (file.is_relative()) file = scene_dir / file;
  const double scale = body.number_or("scale", 1.0);
  if (!(scale > 0)) body.fail("scale", "must be positive");
  geometry::TetMesh tets;
  try {
    tets = geometry::read_tet_mesh(file);
    tets.vertices *= scale;
    // A scene's body may be larger than a finger; 10 m is where grip asset prepare's unit
    // warning starts too.
    geometry::check_soft_body_mesh(tets, file.string(), 10.0);
  } catch (const std::exception& e) {
    body.fail("file", std::string("cannot be used: ") + e.what());
  }
  if (static_cast<double>(tets.tets.rows()) > max_tets) {
    body.fail("file", "holds " + std::to_string(tets.tets.rows()) + " tets, more than the " +
                          number_text("%.0f", max_tets) +
                          " allowed (grip simulate --max-tets moves the limit)");
  }
  if (soft) {
    set_fem_mesh(out, tets);
    return;
  }
  const geometry::SurfaceMesh surface = geometry::boundary_surface(tets);
  out.vertices = surface.vertices;
  out.triangles = surface.triangles;
}

// The body's surface (and tets, for FEM) from its shape keys.
void read_shape(const Table& body, const std::filesystem::path& scene_dir, double max_tets,
                solver::BodyDescription& out) {
  const std::string shape = body.choice("shape", {"box", "sphere", "cylinder", "mesh"});
  const bool soft = solver::body_type_info(out.type).soft;
  if (shape == "mesh" && geometry::is_tet_mesh_file(body.string("file"))) {
    read_tet_mesh_shape(body, scene_dir, max_tets, soft, out);
    return;
  }
  // A sphere of n segments has about n^2 / 2 vertices: 1,024 makes half a million.
  const int segments = body.count_or("segments", 24, 6, 1024);
  double resolution = 0.0;
  if (soft) {
    resolution = body.number("resolution");
    if (!(resolution > 0)) body.fail("resolution", "must be a positive tet edge length (m)");
  } else if (body.has("resolution")) {
    body.fail("resolution", "applies to FEM bodies only (type = \"fem\")");
  }

  geometry::SurfaceMesh surface;
  if (shape == "box") {
    const Eigen::Vector3d size = vec(body.vec3("size"));
    if ((size.array() <= 0).any()) body.fail("size", "must hold three positive extents (m)");
    if (soft) {
      // A structured grid: exact volume, no CGAL meshing needed for boxes.
      check_tet_count(body, resolution, box_tet_count(size, resolution), max_tets);
      set_fem_mesh(out, box_tets(size, resolution));
      return;
    }
    surface = geometry::make_box(size);
  } else if (shape == "sphere") {
    const double radius = body.number("radius");
    if (!(radius > 0)) body.fail("radius", "must be positive (m)");
    surface = geometry::make_sphere(radius, segments, segments / 2);
  } else if (shape == "cylinder") {
    const double radius = body.number("radius");
    const double height = body.number("height");
    if (!(radius > 0)) body.fail("radius", "must be positive (m)");
    if (!(height > 0)) body.fail("height", "must be positive (m)");
    surface = geometry::make_cylinder(radius, height, segments);
  } else {
    std::filesystem::path file = body.string("file");
    if (file.is_relative()) file = scene_dir / file;
    try {
      surface = geometry::read_surface_mesh(file);
    } catch (const std::exception& e) {
      body.fail("file", std::string("cannot be used: ") + e.what());
    }
    const double scale = body.number_or("scale", 1.0);
    if (!(scale > 0)) body.fail("scale", "must be positive");
    surface.vertices *= scale;
  }
  if (soft) {
    check_tet_count(
        body, resolution,
        geometry::estimated_tet_count(std::abs(geometry::surface_volume(surface)), resolution),
        max_tets);
    geometry::TetOptions options;
    options.edge_length = resolution;
    geometry::TetMesh tets;
    try {
      tets = geometry::tetrahedralize(surface, options, body.path());
    } catch (const std::exception& e) {
      body.fail("shape", std::string("could not be tetrahedralized: ") + e.what());
    }
    set_fem_mesh(out, tets);
  } else {
    out.vertices = surface.vertices;
    out.triangles = surface.triangles;
  }
}

// The body's type by the name its `type` key gives (the solver's body registry lists them).
const solver::BodyTypeInfo& body_type(const Table& body) {
  std::vector<std::string_view> names;
  for (const solver::BodyTypeInfo& info : solver::body_types()) names.push_back(info.name);
  const std::string name = body.choice("type", names);
  for (const solver::BodyTypeInfo& info : solver::body_types()) {
    if (info.name == name) return info;
  }
  return solver::body_types().front();  // choice() admits only the names above
}

solver::BodyDescription read_body(const Table& body, const std::filesystem::path& scene_dir,
                                  double max_tets) {
  body.allow({"name",     "type",
              "shape",    "size",
              "radius",   "height",
              "file",     "scale",
              "segments", "resolution",
              "position", "rotation",
              "velocity", "angular_velocity",
              "density",  "youngs",
              "poisson",  "damping",
              "friction", "orthogonality_stiffness",
              "pin",      "keyframe"});
  solver::BodyDescription out;
  out.name = body.string("name");
  const solver::BodyTypeInfo& kind = body_type(body);
  out.type = kind.type;
  read_shape(body, scene_dir, max_tets, out);
  out.pose.position = vec(body.vec3_or("position", {0, 0, 0}));
  out.pose.rotation = rotation_from_degrees(vec(body.vec3_or("rotation", {0, 0, 0})));
  const Eigen::Vector3d velocity = vec(body.vec3_or("velocity", {0, 0, 0}));
  const Eigen::Vector3d angular = vec(body.vec3_or("angular_velocity", {0, 0, 0}));
  if (kind.scripted) {
    out.script.velocity = velocity;
    out.script.angular_velocity = angular;
    for (const Table& key : body.tables("keyframe")) {
      key.allow({"time", "position", "rotation"});
      solver::Keyframe frame;
      frame.time = key.number("time");
      if (!out.script.keyframes.empty() && frame.time <= out.script.keyframes.back().time) {
        key.fail("time", "must increase from one keyframe to the next");
      }
      frame.pose.position = vec(key.vec3("position"));
      frame.pose.rotation = rotation_from_degrees(vec(key.vec3_or("rotation", {0, 0, 0})));
      out.script.keyframes.push_back(frame);
    }
  } else {
    out.velocity = velocity;
    out.angular_velocity = angular;
    if (body.has("keyframe")) body.fail("keyframe", "applies to kinematic bodies only");
  }
  out.material.density = positive(body, "density", out.material.density);
  out.material.friction = body.number_or("friction", out.material.friction);
  if (out.material.friction < 0) body.fail("friction", "must be >= 0");
  if (kind.soft) {
    out.material.youngs = positive(body, "youngs", out.material.youngs);
    out.material.poisson = body.number_or("poisson", out.material.poisson);
    if (!(out.material.poisson > -1 && out.material.poisson < 0.5)) {
      body.fail("poisson", "must lie in (-1, 0.5)");
    }
    out.material.damping = body.number_or("damping", out.material.damping);
    if (!(out.material.damping >= 0)) body.fail("damping", "must be >= 0 (s)");
  } else {
    for (const char* key : {"youngs", "poisson", "damping"}) {
      if (body.has(key)) body.fail(key, "applies to FEM bodies only (type = \"fem\")");
    }
  }
  if (kind.orthogonality) {
    out.orthogonality_stiffness =
        positive(body, "orthogonality_stiffness", out.orthogonality_stiffness);
  } else if (body.has("orthogonality_stiffness")) {
    body.fail("orthogonality_stiffness", "applies to affine bodies only (type = \"affine\")");
  }
  return out;
}

}  // namespace

SceneFile load_scene_file(const std::filesystem::path& file, double max_tets) {
  const config::Document document = config::Document::load(file);
  const Table root = document.root();
  root.allow({"sim", "body", "contact"});
  SceneFile out;
  if (const auto sim = root.optional_table("sim")) read_sim(*sim, out);

  const std::vector<Table> bodies = root.tables("body");
  if (bodies.empty()) root.fail("body", "is missing: a scene needs at least one [[body]]");
  std::map<std::string, int> index_of;
  for (const Table& body : bodies) {
    out.scene.bodies.push_back(read_body(body, file.parent_path(), max_tets));
    if (!index_of.emplace(out.scene.bodies.back().name, index_of.size()).second) {
      body.fail("name", "\"" + out.scene.bodies.back().name + "\" is used by another body");
    }
  }
  auto body_index = [&](const Table& table, std::string_view key, const std::string& name) {
    const auto it = index_of.find(name);
    if (it == index_of.end()) table.fail(key, "names no body: \"" + name + "\"");
    return it->second;
  };

  // Pins: the FEM vertices inside a world-space box follow a kinematic body.
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (const Table& pin : bodies[b].tables("pin")) {
      pin.allow({"body", "min", "max"});
      solver::BodyDescription& body = out.scene.bodies[b];
      if (!solver::body_type_info(body.type).soft) {
        pin.fail("body", "pins apply to FEM bodies only");
      }
      solver::Pin p;
      p.kinematic_body = body_index(pin, "body", pin.string("body"));
      if (!solver::body_type_info(out.scene.bodies[p.kinematic_body].type).scripted) {
        pin.fail("body", "must name a kinematic body");
      }
      const Eigen::Vector3d lo = vec(pin.vec3("min")), hi = vec(pin.vec3("max"));
      const Eigen::Matrix3d r = body.pose.rotation.toRotationMatrix();
      for (Eigen::Index v = 0; v < body.vertices.rows(); ++v) {
        const Eigen::Vector3d x = r * body.vertices.row(v).transpose() + body.pose.position;
        if ((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all()) {
          p.vertices.push_back(static_cast<int>(v));
        }
      }
      if (p.vertices.empty()) pin.fail("min", "and max enclose no vertex of the body");
      body.pins.push_back(p);
    }
  }

  for (const Table& contact : root.tables("contact")) {
    contact.allow({"bodies", "friction"});
    const std::vector<std::string> names = contact.strings("bodies");
    if (names.size() != 2) contact.fail("bodies", "must name exactly two bodies");
    solver::ContactOverride c;
    c.body_a = body_index(contact, "bodies", names[0]);
    c.body_b = body_index(contact, "bodies", names[1]);
    c.friction = contact.number("friction");
    if (c.friction < 0) contact.fail("friction", "must be >= 0");
    out.scene.contacts.push_back(c);
  }

  try {
    solver::Model::build(out.scene);  // validates what only the whole scene can tell
  } catch (const std::invalid_argument& e) {
    throw config::ConfigError(file.string() + ": " + e.what());
  }
  return out;
}

}  // namespace grip::scene
