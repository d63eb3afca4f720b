#pragma once
// Von Mises stress per tetrahedron of a deformed FEM body, from the same stable Neo-Hookean
// material the solver simulates (Cauchy stress sigma = P F^T / J, then sqrt(3/2 s:s)).
#include <Eigen/Core>

#include "src/geometry/mesh.hpp"

namespace grip::metrics {

// `rest` gives the tets and the stress-free shape; `deformed` the same vertices now. Pa, one
// value per tet. Throws std::invalid_argument when the vertex counts differ or a tet is
// degenerate or inverted (IPC never leaves one inverted).
Eigen::VectorXd von_mises_stress(const geometry::TetMesh& rest, const geometry::Vertices& deformed,
                                 double youngs_modulus, double poisson_ratio);

}  // namespace grip::metrics
