#pragma once
// Closed surfaces swept from a 2D profile: revolving a (radius, height) polyline about the
// z axis, and sweeping a circle along a 3D polyline (a tube with flat end caps).
#include <vector>

#include <Eigen/Core>

#include "src/geometry/mesh.hpp"

namespace grip::objects {

// Revolves `profile`, points (r, z) with r >= 0, about the z axis in `segments` steps.
// If `closed_loop` is false the profile must start and end on the axis (r = 0): those ends
// become poles and the rest sweeps to rings (a solid of revolution such as a cup). If it is
// true, the profile is a loop away from the axis (a torus). The result is outward oriented.
geometry::SurfaceMesh revolve_profile(const std::vector<Eigen::Vector2d>& profile, int segments,
                                      bool closed_loop);

// A tube of circular cross-section `radius` around the polyline `path` (at least two points),
// closed by flat caps at both ends; cross-sections are perpendicular to the path. Outward
// oriented.
geometry::SurfaceMesh sweep_tube(const std::vector<Eigen::Vector3d>& path, double radius,
                                 int segments);

// Appends points of the arc of `centre` and `radius` from angle `from` to `to` (radians,
// measured from the +r axis towards +z), `steps` pieces, the start point included only if
// `include_start`.
void append_arc(std::vector<Eigen::Vector2d>& profile, const Eigen::Vector2d& centre, double radius,
                double from, double to, int steps, bool include_start = true);

}  // namespace grip::objects
