#include "src/metrics/von_mises.hpp"

#include <stdexcept>
#include <string>

#include "solver/kernels/neo_hookean.hpp"

namespace grip::metrics {

namespace k = solver::kernels;

Eigen::VectorXd von_mises_stress(const geometry::TetMesh& rest, const geometry::Vertices& deformed,
                                 double youngs_modulus, double poisson_ratio) {
  if (rest.vertices.rows() != deformed.rows()) {
    throw std::invalid_argument("von Mises stress: " + std::to_string(deformed.rows()) +
                                " deformed vertices for a mesh of " +
                                std::to_string(rest.vertices.rows()));
  }
  const k::StableNeoHookeanParameters material =
      k::stable_neo_hookean_parameters(youngs_modulus, poisson_ratio);
  Eigen::VectorXd stress(rest.tets.rows());
  for (Eigen::Index t = 0; t < rest.tets.rows(); ++t) {
    auto corner = [&](const geometry::Vertices& v, int c) -> Eigen::Vector3d {
      return v.row(rest.tets(t, c)).transpose();
    };
    const Eigen::Vector3d x0 = corner(rest.vertices, 0), x1 = corner(rest.vertices, 1),
                          x2 = corner(rest.vertices, 2), x3 = corner(rest.vertices, 3);
    if (!(k::tet_rest_volume(x0, x1, x2, x3) > 0.0)) {
      throw std::invalid_argument("von Mises stress: rest tet " + std::to_string(t) +
                                  " is degenerate or inverted");
    }
    const Eigen::Matrix3d dm_inverse = k::tet_rest_shape_inverse(x0, x1, x2, x3);
    k::Vector12d x;
    for (int c = 0; c < 4; ++c) x.segment<3>(3 * c) = corner(deformed, c);
    const Eigen::Matrix3d f = k::deformation_gradient(x, dm_inverse);
    if (!(f.determinant() > 0.0)) {
      throw std::invalid_argument("von Mises stress: tet " + std::to_string(t) + " is inverted");
    }
    stress[t] = k::von_mises_stress(k::stable_neo_hookean_cauchy_stress(f, material));
  }
  return stress;
}

}  // namespace grip::metrics
