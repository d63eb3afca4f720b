#include "src/scene/primitives.hpp"

#include <Eigen/Geometry>

#include "src/geometry/boundary_surface.hpp"

namespace grip::scene {
namespace {

// Cells per axis of box_tets: about size / cell, at least one.
Eigen::Vector3d box_cells(const Eigen::Vector3d& size, double cell) {
  return (size / cell).array().round().max(1.0).matrix();
}

}  // namespace

solver::BodyDescription surface_body(const std::string& name, solver::BodyType type,
                                     const geometry::SurfaceMesh& mesh,
                                     const Eigen::Vector3d& position) {
  solver::BodyDescription body;
  body.name = name;
  body.type = type;
  body.vertices = mesh.vertices;
  body.triangles = mesh.triangles;
  body.pose.position = position;
  return body;
}

void set_fem_mesh(solver::BodyDescription& body, const geometry::TetMesh& tets) {
  Eigen::VectorXi to_tet;
  const geometry::SurfaceMesh boundary = geometry::boundary_surface(tets, &to_tet);
  body.vertices = tets.vertices;
  body.tets = tets.tets;
  body.triangles = boundary.triangles.unaryExpr([&](int v) { return to_tet[v]; });
}

geometry::TetMesh box_tets(const Eigen::Vector3d& size, double cell) {
  const Eigen::Vector3i n = box_cells(size, cell).cast<int>();
  auto index = [&](int i, int j, int k) { return (k * (n.y() + 1) + j) * (n.x() + 1) + i; };
  geometry::TetMesh mesh;
  mesh.vertices.resize((n.x() + 1) * (n.y() + 1) * (n.z() + 1), 3);
  for (int k = 0; k <= n.z(); ++k)
    for (int j = 0; j <= n.y(); ++j)
      for (int i = 0; i <= n.x(); ++i) {
        const Eigen::Vector3d t(double(i) / n.x(), double(j) / n.y(), double(k) / n.z());
        mesh.vertices.row(index(i, j, k)) = (t.array() - 0.5).matrix().cwiseProduct(size);
      }
  // Kuhn's split: one tet per path from corner 000 to corner 111 along the axes.
  constexpr int kPaths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  mesh.tets.resize(6 * n.x() * n.y() * n.z(), 4);
  int t = 0;
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i)
        for (const auto& path : kPaths) {
          Eigen::Vector3i corner(i, j, k);
          int tet[4];
          tet[0] = index(corner.x(), corner.y(), corner.z());
          for (int step = 0; step < 3; ++step) {
            corner[path[step]] += 1;
            tet[step + 1] = index(corner.x(), corner.y(), corner.z());
          }
          const Eigen::Vector3d a = mesh.vertices.row(tet[0]), b = mesh.vertices.row(tet[1]),
                                c = mesh.vertices.row(tet[2]), d = mesh.vertices.row(tet[3]);
          if ((b - a).cross(c - a).dot(d - a) < 0) std::swap(tet[1], tet[2]);
          mesh.tets.row(t++) << tet[0], tet[1], tet[2], tet[3];
        }
  return mesh;
}

double box_tet_count(const Eigen::Vector3d& size, double cell) {
  return 6.0 * box_cells(size, cell).prod();
}

}  // namespace grip::scene
