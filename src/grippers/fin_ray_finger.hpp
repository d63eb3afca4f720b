#pragma once
// The soft fin-ray finger of the UMI-style gripper: a tapered profile, solid (GRIP's finger) or
// two walls joined by inclined cross ribs (the classic fin-ray), extruded and tetrahedralized,
// with its mount region and TPU material.
#include <vector>

#include "src/geometry/mesh.hpp"

namespace grip::grippers {

// Finger frame: the profile lies in the (y, z) plane and is extruded along x, centred on x = 0.
// z runs from the mount face (z = 0) to the tip (z = length); the contact wall's outer face is
// the plane y = 0 with outward normal -y, and the back wall slants from y = base_width at the
// mount to y = tip_width at the tip. Lengths in metres.
// The production finger is the finger body GRIP simulates (its released models'
// finray_finger_L_body meshes: a solid wedge 123.5 mm from the mount to the tip, 41.5 mm deep at
// the mount, about 3.3 mm at the tip, 26 mm wide; docs/assets.md): solid, with a straight back
// where GRIP's is convex and without the small knob on its back. `hollow` makes the
// classic fin-ray of walls and cross ribs instead (the 80 mm variant below).
struct FinRayOptions {
  double length = 0.1235;      // mount face to tip
  double base_width = 0.0415;  // profile width at the mount (y)
  double tip_width = 0.0033;   // profile width at the tip (y)
  double depth = 0.026;        // extrusion: the finger's width along x
  // A solid profile measured by the fields above, or walls, a mount plate and ribs around
  // cavities, measured by those below.
  bool hollow = false;
  double wall_thickness = 0.002;  // contact wall, back wall and tip cap
  double rib_thickness = 0.0016;
  double base_thickness = 0.005;  // the mount region pinned to the jaw (a hollow finger's plate)
  int rib_count = 5;
  double rib_angle_deg = 12.0;  // ribs rise by this angle from the contact wall to the back wall
  double top_cavity_width = 0.005;  // the cavity ends (under a solid tip) where it is this narrow
  double edge_length = 0.006;       // largest triangle edge of the profile mesh
  // Tet layers across the depth; an even count puts tet faces on the mid-plane, where a
  // centred grasp presses (docs/assets.md, "The fin-ray finger's mesh").
  int layers = 4;
};

// grip's first finger, a hollow fin-ray 80 mm long, 30 mm deep at the mount and 22 mm wide, with
// five ribs, meshed at 3.6 mm edges: a named variant (jobs/grippers/fin-ray-80mm.toml describes
// it from a file), and the tests' small finger.
FinRayOptions fin_ray_80mm_options();

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
