#include "src/grippers/surface_merge.hpp"

namespace grip::grippers {

void append_transformed(geometry::SurfaceMesh& mesh, const geometry::SurfaceMesh& part,
                        const Eigen::Affine3d& transform) {
  const Eigen::Index v0 = mesh.vertices.rows();
  const Eigen::Index t0 = mesh.triangles.rows();
  mesh.vertices.conservativeResize(v0 + part.vertices.rows(), 3);
  mesh.triangles.conservativeResize(t0 + part.triangles.rows(), 3);
  for (Eigen::Index i = 0; i < part.vertices.rows(); ++i) {
    mesh.vertices.row(v0 + i) = (transform * part.vertices.row(i).transpose()).transpose();
  }
  const bool mirrored = transform.linear().determinant() < 0.0;
  for (Eigen::Index i = 0; i < part.triangles.rows(); ++i) {
    const Eigen::Vector3i t = part.triangles.row(i).transpose().array() + static_cast<int>(v0);
    mesh.triangles.row(t0 + i) << t.x(), mirrored ? t.z() : t.y(), mirrored ? t.y() : t.z();
  }
}

}  // namespace grip::grippers
