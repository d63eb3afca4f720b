#pragma once
// The procedural object library: named categories of graspable shapes, each with parameter
// ranges (metres), generating closed outward surfaces. Sampling is deterministic for a seed.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "src/geometry/mesh.hpp"

namespace grip::objects {

enum class ObjectCategory {
  kBox,
  kCylinder,
  kSphere,
  kEllipsoid,
  kCapsule,
  kCone,
  kTorus,
  kBottle,
  kCup,
  kMug,
  kBowl,
  kPlate,
  // Large enough to need two grippers (GRIP's bimanual half), yet thin enough across for one
  // gripper or hand to close on: a long bar (box) and a long rod (cylinder).
  kBar,
  kRod,
};

struct ParameterRange {
  std::string_view name;
  double min;  // m
  double max;  // m
};

// A shape: its category and one value per parameter, in the order of parameter_ranges().
struct ObjectShape {
  ObjectCategory category;
  std::vector<double> parameters;
};

std::span<const ObjectCategory> all_object_categories();
std::string_view category_name(ObjectCategory category);
// Throws std::invalid_argument listing the known names.
ObjectCategory parse_object_category(std::string_view name);

std::span<const ParameterRange> parameter_ranges(ObjectCategory category);

// Each parameter drawn uniformly in its range. Same category and seed, same shape.
ObjectShape sample_shape(ObjectCategory category, std::uint64_t seed);

// The thinnest part of the shape (m): a wall, a plate, a tube radius. A tet edge length of
// about half of it resolves the shape with a few tets across.
double thinnest_feature(const ObjectShape& shape);

// The tet edge length to mesh `shape` scaled by `scale` with: `requested`, or its thinnest part
// over `tets_across` when that is smaller. An edge longer than a wall is thick leaves slivers (a
// mug's handle meshed at 8 mm: dihedral angles of 1 to 2 degrees).
inline constexpr double kDefaultTetsAcross = 2.0;
inline constexpr double kMinTetsAcross = 1.0;
inline constexpr double kMaxTetsAcross = 8.0;
double tet_edge_for(const ObjectShape& shape, double scale, double requested,
                    double tets_across = kDefaultTetsAcross);

// The closed, outward, manifold surface of the shape, centred on the origin's vertical axis
// and standing on z = 0 (a torus and a sphere-like shape lie with their lowest point at z =
// 0). `segments` sets the angular resolution of round parts. Throws std::invalid_argument if
// a parameter is missing, outside its range, or the parameters contradict each other.
geometry::SurfaceMesh generate_surface(const ObjectShape& shape, int segments = 48);

}  // namespace grip::objects
