#pragma once
// Closed triangle meshes of simple solids (boxes, capsules, cylinders, spheres) used as link
// geometry of the generated hands and jaws, URDF <box>/<cylinder>/<sphere> elements and the
// primitive shapes of scene files.
#include <Eigen/Core>

#include "src/geometry/mesh.hpp"

namespace grip::geometry {

// Axis-aligned box centred at the origin with edge lengths `size` (m); 8 vertices, 12 triangles.
SurfaceMesh make_box(const Eigen::Vector3d& size);

// Capsule whose axis runs along +x from x = 0 to x = `length` (the total extent, both rounded
// caps included), radius `radius`; `segments` vertices around the axis (>= 3) and `rings`
// latitude steps per hemispherical cap (>= 1). Needs length >= 2 * radius; length == 2 * radius
// is a sphere touching x = 0.
SurfaceMesh make_capsule(double radius, double length, int segments, int rings);

// Cylinder along z centred at the origin (the URDF convention), `segments` vertices per rim.
SurfaceMesh make_cylinder(double radius, double length, int segments);

// Sphere centred at the origin (a capsule with no straight part).
SurfaceMesh make_sphere(double radius, int segments, int rings);

}  // namespace grip::geometry
