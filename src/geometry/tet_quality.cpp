#include "src/geometry/tet_quality.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace grip::geometry {

TetQuality tet_quality(const TetMesh& mesh, double sliver_bound_deg) {
  // Each edge is shared by the faces opposite the two corners k, l not on it; its interior
  // dihedral angle is acos(-n_k . n_l) with n the outward unit normals of those faces.
  constexpr std::array<std::array<int, 2>, 6> kOppositeFacePairs = {
      {{2, 3}, {1, 3}, {1, 2}, {0, 3}, {0, 2}, {0, 1}}};
  TetQuality quality;
  quality.min_dihedral_deg = std::numeric_limits<double>::infinity();
  quality.max_dihedral_deg = 0.0;
  quality.min_volume = std::numeric_limits<double>::infinity();
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) {
    std::array<Eigen::Vector3d, 4> x;
    for (int k = 0; k < 4; ++k) x[k] = mesh.vertices.row(mesh.tets(t, k));
    const double volume = (x[1] - x[0]).cross(x[2] - x[0]).dot(x[3] - x[0]) / 6.0;
    quality.total_volume += volume;
    quality.min_volume = std::min(quality.min_volume, volume);
    if (volume <= 0.0) ++quality.inverted_count;

    // Normal of the face opposite corner k, pointing away from corner k.
    std::array<Eigen::Vector3d, 4> normal;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d& a = x[(k + 1) % 4];
      const Eigen::Vector3d& b = x[(k + 2) % 4];
      const Eigen::Vector3d& c = x[(k + 3) % 4];
      Eigen::Vector3d n = (b - a).cross(c - a);
      if (n.dot(x[k] - a) > 0.0) n = -n;
      normal[k] = n.normalized();
    }
    bool sliver = false;
    for (const auto& [k, l] : kOppositeFacePairs) {
      const double cosine = std::clamp(-normal[k].dot(normal[l]), -1.0, 1.0);
      const double angle = std::acos(cosine) * 180.0 / std::numbers::pi;
      quality.min_dihedral_deg = std::min(quality.min_dihedral_deg, angle);
      quality.max_dihedral_deg = std::max(quality.max_dihedral_deg, angle);
      sliver = sliver || angle < sliver_bound_deg;
    }
    if (sliver) ++quality.sliver_count;
  }
  if (mesh.tets.rows() == 0) {
    quality.min_dihedral_deg = 0.0;
    quality.min_volume = 0.0;
  }
  return quality;
}

}  // namespace grip::geometry
