#include "src/grippers/fin_ray_finger.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

namespace grip::grippers {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Tds = CGAL::Triangulation_data_structure_2<CGAL::Delaunay_mesh_vertex_base_2<Kernel>,
                                                 CGAL::Delaunay_mesh_face_base_2<Kernel>>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
using Mesher = CGAL::Delaunay_mesher_2<Cdt, Criteria>;

// Profile points are (y, z).
using Polygon = std::vector<Eigen::Vector2d>;

// The half-plane n . p <= c.
struct HalfPlane {
  Eigen::Vector2d n;
  double c;
};

// Clips a convex polygon to a half-plane (Sutherland-Hodgman, one edge).
Polygon clip(const Polygon& polygon, const HalfPlane& h) {
  Polygon out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d& q = polygon[(i + 1) % polygon.size()];
    const double dp = h.n.dot(p) - h.c;
    const double dq = h.n.dot(q) - h.c;
    if (dp <= 0.0) out.push_back(p);
    if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) {
      out.push_back(p + (q - p) * (dp / (dp - dq)));
    }
  }
  return out;
}

double signed_area(const Polygon& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d& q = polygon[(i + 1) % polygon.size()];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * twice;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("fin-ray finger: " + what);
}

struct Profile {
  Polygon outer;               // counter-clockwise
  std::vector<Polygon> holes;  // the cavities between ribs, counter-clockwise
};

Profile make_profile(const FinRayOptions& o) {
  require(o.length > 0.0 && o.base_width > 0.0 && o.tip_width > 0.0 && o.depth > 0.0,
          "length, base_width, tip_width and depth must be positive");
  require(o.tip_width < o.base_width, "tip_width must be smaller than base_width");
  require(o.wall_thickness > 0.0 && o.rib_thickness > 0.0 && o.base_thickness > 0.0,
          "wall, rib and base thicknesses must be positive");
  require(o.rib_count >= 0, "rib_count must not be negative");
  require(std::abs(o.rib_angle_deg) < 60.0, "rib_angle_deg must lie in (-60, 60)");
  require(o.edge_length > 0.0 && o.layers >= 1, "edge_length must be positive and layers >= 1");

  Profile profile;
  profile.outer = {{0.0, 0.0}, {o.base_width, 0.0}, {o.tip_width, o.length}, {0.0, o.length}};
  if (!o.hollow) return profile;

  // The cavity: inside the contact wall, above the mount plate, inside the back wall, below
  // the height where it narrows to top_cavity_width.
  const Eigen::Vector2d back_dir =
      (Eigen::Vector2d(o.tip_width, o.length) - Eigen::Vector2d(o.base_width, 0.0)).normalized();
  const Eigen::Vector2d back_normal(back_dir.y(), -back_dir.x());  // outward (+y side)
  const double back_c = back_normal.dot(Eigen::Vector2d(o.base_width, 0.0)) - o.wall_thickness;
  Polygon cavity = profile.outer;
  cavity = clip(cavity, {{-1.0, 0.0}, -o.wall_thickness});
  cavity = clip(cavity, {{0.0, -1.0}, -o.base_thickness});
  cavity = clip(cavity, {back_normal, back_c});
  // The inner back wall is n . (y, z) = back_c; the cavity is top_cavity_width wide at `top`.
  const double top =
      (back_c - back_normal.x() * (o.wall_thickness + o.top_cavity_width)) / back_normal.y();
  require(top > o.base_thickness + (o.rib_count + 1) * o.rib_thickness &&
              top < o.length - o.wall_thickness,
          "the walls leave no room for a cavity; make the finger wider or the walls thinner");
  cavity = clip(cavity, {{0.0, 1.0}, top});

  // Rib k's centre line meets the contact wall's inner face at z_k, evenly spaced, and rises
  // by rib_angle towards the back wall.
  const double angle = o.rib_angle_deg * std::numbers::pi / 180.0;
  const Eigen::Vector2d rib_normal(-std::sin(angle), std::cos(angle));
  Polygon rest = cavity;
  for (int k = 1; k <= o.rib_count; ++k) {
    const double z_k = o.base_thickness + (top - o.base_thickness) * k / (o.rib_count + 1);
    const double c_k = rib_normal.dot(Eigen::Vector2d(o.wall_thickness, z_k));
    profile.holes.push_back(clip(rest, {rib_normal, c_k - 0.5 * o.rib_thickness}));
    rest = clip(rest, {-rib_normal, -(c_k + 0.5 * o.rib_thickness)});
  }
  profile.holes.push_back(rest);
  for (const Polygon& hole : profile.holes) {
    require(hole.size() >= 3 && signed_area(hole) > o.rib_thickness * o.rib_thickness,
            "the ribs leave an empty cavity; use fewer ribs or a smaller rib angle");
  }
  return profile;
}

// Inserts a closed polygon as constraints.
void insert_polygon(Cdt& cdt, const Polygon& polygon) {
  std::vector<Cdt::Vertex_handle> handles;
  for (const Eigen::Vector2d& p : polygon) handles.push_back(cdt.insert(Cdt::Point(p.x(), p.y())));
  for (std::size_t i = 0; i < handles.size(); ++i) {
    cdt.insert_constraint(handles[i], handles[(i + 1) % handles.size()]);
  }
}

double tet_volume(const geometry::Vertices& v, const std::array<int, 4>& t) {
  const Eigen::Vector3d a = v.row(t[0]).transpose();
  return (v.row(t[1]).transpose() - a)
             .cross(v.row(t[2]).transpose() - a)
             .dot(v.row(t[3]).transpose() - a) /
         6.0;
}

}  // namespace

FinRayOptions fin_ray_80mm_options() {
  FinRayOptions o;
  o.length = 0.080;
  o.base_width = 0.030;
  o.tip_width = 0.004;
  o.depth = 0.022;
  o.hollow = true;
  o.edge_length = 0.0036;
  o.layers = 4;
  return o;
}

FinRayFinger make_fin_ray_finger(const FinRayOptions& options) {
  const Profile profile = make_profile(options);

  Cdt cdt;
  insert_polygon(cdt, profile.outer);
  std::vector<Cdt::Point> seeds;
  for (const Polygon& hole : profile.holes) {
    insert_polygon(cdt, hole);
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& p : hole) centroid += p;
    centroid /= static_cast<double>(hole.size());  // inside: the holes are convex
    seeds.emplace_back(centroid.x(), centroid.y());
  }
  Mesher mesher(cdt);
  mesher.set_criteria(Criteria(0.125, options.edge_length));  // 0.125: min angle ~20.7 deg
  mesher.set_seeds(seeds.begin(), seeds.end(), /*mark=*/false);
  mesher.refine_mesh();

  // Number the profile vertices that belong to a meshed triangle, in CGAL's iteration order
  // (deterministic for the same input).
  std::map<Cdt::Vertex_handle, int> index;
  std::vector<Eigen::Vector2d> points;
  std::vector<std::array<int, 3>> triangles;
  for (auto face = cdt.finite_faces_begin(); face != cdt.finite_faces_end(); ++face) {
    if (!face->is_in_domain()) continue;
    std::array<int, 3> triangle{};
    for (int i = 0; i < 3; ++i) {
      const auto vertex = face->vertex(i);
      auto [it, inserted] = index.try_emplace(vertex, static_cast<int>(points.size()));
      if (inserted) points.emplace_back(vertex->point().x(), vertex->point().y());
      triangle[static_cast<std::size_t>(i)] = it->second;
    }
    triangles.push_back(triangle);
  }

  // Extrude through the layers: vertex (layer l, profile vertex i) gets index l * n + i.
  const int n = static_cast<int>(points.size());
  const int layers = options.layers;
  FinRayFinger finger;
  finger.mesh.vertices.resize(static_cast<Eigen::Index>(n) * (layers + 1), 3);
  for (int l = 0; l <= layers; ++l) {
    const double x = options.depth * (static_cast<double>(l) / layers - 0.5);
    for (int i = 0; i < n; ++i) {
      finger.mesh.vertices.row(l * n + i) << x, points[static_cast<std::size_t>(i)].x(),
          points[static_cast<std::size_t>(i)].y();
    }
  }
  // Prism (a, b, c) -> (a', b', c') with a < b < c: each side quad is cut by the diagonal from
  // its smallest-index vertex (a bottom vertex), which both prisms sharing it agree on.
  finger.mesh.tets.resize(static_cast<Eigen::Index>(triangles.size()) * layers * 3, 4);
  Eigen::Index row = 0;
  for (int l = 0; l < layers; ++l) {
    for (std::array<int, 3> t : triangles) {
      std::sort(t.begin(), t.end());
      const int a = l * n + t[0], b = l * n + t[1], c = l * n + t[2];
      const int a1 = a + n, b1 = b + n, c1 = c + n;
      for (std::array<int, 4> tet :
           {std::array<int, 4>{a, b, c, c1}, std::array<int, 4>{a, b, b1, c1},
            std::array<int, 4>{a, a1, b1, c1}}) {
        if (tet_volume(finger.mesh.vertices, tet) < 0.0) std::swap(tet[2], tet[3]);
        finger.mesh.tets.row(row++) << tet[0], tet[1], tet[2], tet[3];
      }
    }
  }

  const double mount_z = options.base_thickness * (1.0 + 1e-9);
  for (Eigen::Index v = 0; v < finger.mesh.vertices.rows(); ++v) {
    if (finger.mesh.vertices(v, 2) <= mount_z) finger.mount_vertices.push_back(static_cast<int>(v));
  }
  finger.profile_area = signed_area(profile.outer);
  for (const Polygon& hole : profile.holes) finger.profile_area -= signed_area(hole);
  return finger;
}

}  // namespace grip::grippers
