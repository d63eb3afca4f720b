#pragma once
// The soft fin-ray finger of the UMI-style gripper: a tapered two-wall profile joined by
// inclined cross ribs, extruded and tetrahedralized, with its mount region and TPU material.
#include <vector>

#include "src/geometry/mesh.hpp"

namespace grip::grippers {

// Finger frame: the profile lies in the (y, z) plane and is extruded along x, centred on x = 0.
// z runs from the mount face (z = 0) to the tip (z = length); the contact wall's outer face is
// the plane y = 0 with outward normal -y, and the back wall slants from y = base_width at the
// mount to y = tip_width at the tip. Lengths in metres.
struct FinRayOptions {
  double length = 0.080;          // mount face to tip
  double base_width = 0.030;      // profile width at the mount (y)
  double tip_width = 0.004;       // profile width at the tip (y)
  double depth = 0.022;           // extrusion: the finger's width along x
  double wall_thickness = 0.002;  // contact wall, back wall and tip cap
  double rib_thickness = 0.0016;
  double base_thickness = 0.005;  // the mount plate, clamped in the jaw
  int rib_count = 5;
  double rib_angle_deg = 12.0;  // ribs rise by this angle from the contact wall to the back wall
  double top_cavity_width = 0.005;  // the cavity ends (under a solid tip) where it is this narrow
  double edge_length = 0.0036;      // largest triangle edge of the profile mesh
  // Tet layers across the depth. Four: within 0.07 mm (pose) of eight at 40 % of the cost
  // (grip bench accuracy, mesh sweep: docs/assets.md). Fewer stretch the tets along the depth
  // (two: 366 slivers) or move the grasp (one: 2.4 mm).
  int layers = 4;
};

// TPU/TPE as printed for UMI fingers. E and mu are GRIP's (paper, Sec. III-D); density is that
// of TPU 95A; Poisson's ratio and the damping are our choices for a soft elastomer under linear
// tets.
struct FinRayMaterial {
  double youngs_modulus = 9.4e6;  // Pa
  double poisson_ratio = 0.4;
  double density = 1200.0;  // kg/m^3
  double friction = 3.5;    // dry friction coefficient against objects
  // Rayleigh stiffness-proportional damping (solver::Material::damping): a loss factor
  // beta omega of 0.16 at 5 Hz, where an object swings on the bending fingers, of the order
  // elastomers show; without it only implicit Euler damps that swing, by an amount that depends
  // on dt (docs/trial.md, "Verdict").
  double damping = 5e-3;  // s
};

// The mesh resolutions the command line accepts (grip trial --finger-layers, --finger-edge).
// Their ends are far past any mesh worth a trial: 1 mm edges give 3,047 profile triangles
// (about 292,000 tets at 32 layers), 10 mm edges 147.
inline constexpr int kMaxFinRayLayers = 32;
inline constexpr double kMinFinRayEdge = 0.001;  // m
inline constexpr double kMaxFinRayEdge = 0.01;   // m

struct FinRayFinger {
  geometry::TetMesh mesh;           // finger frame, positively oriented tets
  std::vector<int> mount_vertices;  // increasing; the vertices with z <= base_thickness
  FinRayMaterial material;
  double profile_area = 0.0;  // exact area of the meshed profile (m^2)
};

// Builds the finger: CGAL's constrained Delaunay mesher triangulates the profile (minimum
// angle about 20.7 degrees, edges at most edge_length), and each triangle is extruded through
// `layers` prisms, each split into three positive tets by the smallest-index diagonal rule
// (conforming across neighbouring prisms). Throws std::invalid_argument for options that do
// not describe a valid profile.
FinRayFinger make_fin_ray_finger(const FinRayOptions& options = {});

}  // namespace grip::grippers
