#include "src/objects/object_library.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "src/geometry/boolean_union.hpp"
#include "src/objects/seeded_uniform.hpp"
#include "src/objects/surface_of_revolution.hpp"

namespace grip::objects {
namespace {

using geometry::SurfaceMesh;
using Profile = std::vector<Eigen::Vector2d>;
constexpr double kPi = std::numbers::pi;

struct CategoryInfo {
  ObjectCategory category;
  std::string_view name;
  std::vector<ParameterRange> ranges;
};

const std::vector<CategoryInfo>& categories() {
  static const std::vector<CategoryInfo> kCategories = {
      {ObjectCategory::kBox,
       "box",
       {{"size_x", 0.03, 0.20}, {"size_y", 0.03, 0.20}, {"size_z", 0.03, 0.20}}},
      {ObjectCategory::kCylinder, "cylinder", {{"radius", 0.015, 0.06}, {"height", 0.04, 0.25}}},
      {ObjectCategory::kSphere, "sphere", {{"radius", 0.02, 0.08}}},
      {ObjectCategory::kEllipsoid,
       "ellipsoid",
       {{"semi_axis_x", 0.02, 0.08}, {"semi_axis_y", 0.02, 0.08}, {"semi_axis_z", 0.02, 0.08}}},
      {ObjectCategory::kCapsule,
       "capsule",
       {{"radius", 0.015, 0.05}, {"cylinder_length", 0.02, 0.15}}},
      {ObjectCategory::kCone, "cone", {{"base_radius", 0.02, 0.08}, {"height", 0.04, 0.20}}},
      {ObjectCategory::kTorus,
       "torus",
       {{"major_radius", 0.03, 0.08}, {"minor_radius", 0.008, 0.025}}},
      {ObjectCategory::kBottle,
       "bottle",
       {{"radius", 0.025, 0.05},
        {"body_height", 0.08, 0.20},
        {"neck_radius", 0.01, 0.02},
        {"neck_height", 0.02, 0.06}}},
      {ObjectCategory::kCup,
       "cup",
       {{"radius", 0.03, 0.05},
        {"height", 0.06, 0.12},
        {"wall", 0.004, 0.008},
        {"bottom", 0.005, 0.01}}},
      {ObjectCategory::kMug,
       "mug",
       {{"radius", 0.035, 0.05},
        {"height", 0.08, 0.12},
        {"wall", 0.004, 0.008},
        {"bottom", 0.005, 0.01},
        {"handle_radius", 0.018, 0.028},
        {"handle_thickness", 0.004, 0.007}}},
      {ObjectCategory::kBowl, "bowl", {{"radius", 0.05, 0.10}, {"wall", 0.004, 0.008}}},
      {ObjectCategory::kPlate,
       "plate",
       {{"size_x", 0.08, 0.20}, {"size_y", 0.06, 0.15}, {"thickness", 0.004, 0.012}}},
      // A fin-ray gripper opens to 85 mm and a LEAP hand closes around about 10 cm: at most
      // 7 cm across, with the synthesis margin to spare.
      {ObjectCategory::kBar,
       "bar",
       {{"length", 0.20, 0.60}, {"width", 0.03, 0.07}, {"height", 0.03, 0.07}}},
      {ObjectCategory::kRod, "rod", {{"radius", 0.015, 0.035}, {"length", 0.25, 0.60}}},
  };
  return kCategories;
}

const CategoryInfo& info(ObjectCategory category) {
  for (const auto& entry : categories()) {
    if (entry.category == category) return entry;
  }
  throw std::invalid_argument("unknown object category");
}

SurfaceMesh box(double x, double y, double z) {
  SurfaceMesh mesh;
  mesh.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.row(i) << ((i & 1) ? 0.5 : -0.5) * x, ((i & 2) ? 0.5 : -0.5) * y,
        ((i & 4) ? z : 0.0);
  }
  // Corner i has bits (x, y, z); faces counter-clockwise seen from outside.
  mesh.triangles.resize(12, 3);
  mesh.triangles << 0, 2, 3, 0, 3, 1,  // z = 0
      4, 5, 7, 4, 7, 6,                // z = top
      0, 1, 5, 0, 5, 4,                // y = -
      2, 6, 7, 2, 7, 3,                // y = +
      0, 4, 6, 0, 6, 2,                // x = -
      1, 3, 7, 1, 7, 5;                // x = +
  return mesh;
}

int arc_steps(int segments, double angle) {
  return std::max(2, static_cast<int>(std::ceil(segments * angle / (2.0 * kPi))));
}

// A solid of revolution standing on z = 0 from bottom to top along its outside.
SurfaceMesh cylinder(double r, double h, int segments) {
  return revolve_profile({{0.0, 0.0}, {r, 0.0}, {r, h}, {0.0, h}}, segments, false);
}

SurfaceMesh ellipsoid(double a, double b, double c, int segments) {
  Profile profile;
  append_arc(profile, {0.0, 0.0}, 1.0, -kPi / 2, kPi / 2, arc_steps(segments, kPi));
  profile.front().x() = 0.0;
  profile.back().x() = 0.0;
  SurfaceMesh mesh = revolve_profile(profile, segments, false);
  mesh.vertices.col(0) *= a;
  mesh.vertices.col(1) *= b;
  mesh.vertices.col(2) = (mesh.vertices.col(2).array() + 1.0) * c;
  return mesh;
}

SurfaceMesh capsule(double r, double length, int segments) {
  Profile profile;
  const int steps = arc_steps(segments, kPi / 2);
  append_arc(profile, {0.0, r}, r, -kPi / 2, 0.0, steps);
  append_arc(profile, {0.0, r + length}, r, 0.0, kPi / 2, steps);
  profile.front().x() = 0.0;
  profile.back().x() = 0.0;
  return revolve_profile(profile, segments, false);
}

SurfaceMesh torus(double major, double minor, int segments) {
  Profile profile;
  append_arc(profile, {major, minor}, minor, 0.0, 2.0 * kPi, segments);
  profile.pop_back();  // the loop closes itself
  return revolve_profile(profile, segments, true);
}

SurfaceMesh bottle(double r, double body, double neck_r, double neck_h, int segments) {
  const double shoulder = r - neck_r;  // a 45-degree shoulder
  return revolve_profile({{0.0, 0.0},
                          {r, 0.0},
                          {r, body},
                          {neck_r, body + shoulder},
                          {neck_r, body + shoulder + neck_h},
                          {0.0, body + shoulder + neck_h}},
                         segments, false);
}

SurfaceMesh cup(double r, double h, double wall, double bottom, int segments) {
  return revolve_profile(
      {{0.0, 0.0}, {r, 0.0}, {r, h}, {r - wall, h}, {r - wall, bottom}, {0.0, bottom}}, segments,
      false);
}

SurfaceMesh mug(double r, double h, double wall, double bottom, double handle_r, double handle_t,
                int segments) {
  const SurfaceMesh body = cup(r, h, wall, bottom, segments);
  // A half-ring handle in the x-z plane; its ends reach past the outer wall to the middle of
  // the wall, so the union joins cleanly without poking into the cavity.
  const double extra = std::asin(std::min(1.0, wall / (2.0 * handle_r)));
  const double z_mid = 0.5 * (bottom + h);
  std::vector<Eigen::Vector3d> path;
  const int steps = arc_steps(segments, kPi + 2 * extra);
  for (int i = 0; i <= steps; ++i) {
    const double angle = -(kPi / 2 + extra) + (kPi + 2 * extra) * i / steps;
    path.emplace_back(r + handle_r * std::cos(angle), 0.0, z_mid + handle_r * std::sin(angle));
  }
  const SurfaceMesh handle = sweep_tube(path, handle_t, std::max(12, segments / 3));
  return geometry::boolean_union(body, handle, "mug body and handle");
}

SurfaceMesh bowl(double r, double wall, int segments) {
  Profile profile;
  const int steps = arc_steps(segments, kPi / 2);
  append_arc(profile, {0.0, r}, r, -kPi / 2, 0.0, steps);
  append_arc(profile, {0.0, r}, r - wall, 0.0, -kPi / 2, steps);
  profile.front().x() = 0.0;
  profile.back().x() = 0.0;
  return revolve_profile(profile, segments, false);
}

void check_shape(const ObjectShape& shape) {
  const CategoryInfo& entry = info(shape.category);
  if (shape.parameters.size() != entry.ranges.size()) {
    throw std::invalid_argument("object '" + std::string(entry.name) + "' takes " +
                                std::to_string(entry.ranges.size()) + " parameters, got " +
                                std::to_string(shape.parameters.size()));
  }
  for (std::size_t i = 0; i < entry.ranges.size(); ++i) {
    const ParameterRange& range = entry.ranges[i];
    const double value = shape.parameters[i];
    if (!(value >= range.min * (1.0 - 1e-12) && value <= range.max * (1.0 + 1e-12))) {
      throw std::invalid_argument("object '" + std::string(entry.name) +
                                  "': " + std::string(range.name) + " = " + std::to_string(value) +
                                  " m is outside [" + std::to_string(range.min) + ", " +
                                  std::to_string(range.max) + "] m");
    }
  }
}

}  // namespace

std::span<const ObjectCategory> all_object_categories() {
  static const std::vector<ObjectCategory> kAll = [] {
    std::vector<ObjectCategory> all;
    for (const auto& entry : categories()) all.push_back(entry.category);
    return all;
  }();
  return kAll;
}

std::string_view category_name(ObjectCategory category) { return info(category).name; }

ObjectCategory parse_object_category(std::string_view name) {
  std::string known;
  for (const auto& entry : categories()) {
    if (entry.name == name) return entry.category;
    known += (known.empty() ? "" : ", ") + std::string(entry.name);
  }
  throw std::invalid_argument("unknown object category '" + std::string(name) +
                              "'; known categories: " + known);
}

std::span<const ParameterRange> parameter_ranges(ObjectCategory category) {
  return info(category).ranges;
}

ObjectShape sample_shape(ObjectCategory category, std::uint64_t seed) {
  SeededUniform uniform(seed, static_cast<std::uint32_t>(category));
  ObjectShape shape{category, {}};
  for (const ParameterRange& range : parameter_ranges(category)) {
    shape.parameters.push_back(uniform(range.min, range.max));
  }
  return shape;
}

double thinnest_feature(const ObjectShape& shape) {
  check_shape(shape);
  const std::vector<double>& p = shape.parameters;
  switch (shape.category) {
    case ObjectCategory::kBox:
      return std::min({p[0], p[1], p[2]});
    case ObjectCategory::kCylinder:
    case ObjectCategory::kCone:
      return std::min(2.0 * p[0], p[1]);
    case ObjectCategory::kSphere:
    case ObjectCategory::kCapsule:
      return 2.0 * p[0];
    case ObjectCategory::kEllipsoid:
      return 2.0 * std::min({p[0], p[1], p[2]});
    case ObjectCategory::kTorus:
      return 2.0 * p[1];
    case ObjectCategory::kBottle:
      return 2.0 * p[2];
    case ObjectCategory::kCup:
      return std::min(p[2], p[3]);
    case ObjectCategory::kMug:
      return std::min({p[2], p[3], 2.0 * p[5]});
    case ObjectCategory::kBowl:
      return p[1];
    case ObjectCategory::kPlate:
      return p[2];
    case ObjectCategory::kBar:
      return std::min(p[1], p[2]);
    case ObjectCategory::kRod:
      return p[0];  // a long rod's round section needs a few tets across its radius
  }
  throw std::invalid_argument("unknown object category");
}

double tet_edge_for(const ObjectShape& shape, double scale, double requested, double tets_across) {
  return std::min(requested, scale * thinnest_feature(shape) / tets_across);
}

SurfaceMesh generate_surface(const ObjectShape& shape, int segments) {
  check_shape(shape);
  if (segments < 8) throw std::invalid_argument("object surface: use at least 8 segments");
  const std::vector<double>& p = shape.parameters;
  switch (shape.category) {
    case ObjectCategory::kBox:
      return box(p[0], p[1], p[2]);
    case ObjectCategory::kCylinder:
      return cylinder(p[0], p[1], segments);
    case ObjectCategory::kSphere:
      return ellipsoid(p[0], p[0], p[0], segments);
    case ObjectCategory::kEllipsoid:
      return ellipsoid(p[0], p[1], p[2], segments);
    case ObjectCategory::kCapsule:
      return capsule(p[0], p[1], segments);
    case ObjectCategory::kCone:
      return revolve_profile({{0.0, 0.0}, {p[0], 0.0}, {0.0, p[1]}}, segments, false);
    case ObjectCategory::kTorus:
      return torus(p[0], p[1], segments);
    case ObjectCategory::kBottle:
      return bottle(p[0], p[1], p[2], p[3], segments);
    case ObjectCategory::kCup:
      return cup(p[0], p[1], p[2], p[3], segments);
    case ObjectCategory::kMug:
      return mug(p[0], p[1], p[2], p[3], p[4], p[5], segments);
    case ObjectCategory::kBowl:
      return bowl(p[0], p[1], segments);
    case ObjectCategory::kPlate:
    case ObjectCategory::kBar:
      return box(p[0], p[1], p[2]);
    case ObjectCategory::kRod:
      return cylinder(p[0], p[1], segments);
  }
  throw std::invalid_argument("unknown object category");
}

}  // namespace grip::objects
