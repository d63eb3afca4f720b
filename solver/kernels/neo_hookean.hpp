#pragma once
// Stable Neo-Hookean elasticity of one linear tetrahedron (Smith et al. 2018): deformation
// gradient, energy density, first Piola stress, the tet's 12-vector gradient and 12x12 Hessian
// (optionally PSD-projected), and the von Mises stress of its Cauchy stress.
//
// Energy density (Smith et al. 2018, Eq. 14 without the optional log term, dropped constant):
//   Psi(F) = mu/2 (tr(F^T F) - 3) - mu (J - 1) + lambda/2 (J - 1)^2,   J = det F.
// Psi(I) = 0 and P(I) = 0 (rest is stress-free). Linearizing at F = I gives
// mu |eps|^2 + (lambda - mu)/2 tr(eps)^2, so matching linear elasticity with Lame parameters
// (mu_L, lambda_L) needs the reparametrization mu = mu_L, lambda = lambda_L + mu_L.
// Unlike classic Neo-Hookean there is no log(J): the energy stays finite for J <= 0 (inverted
// elements get a restoring force), which IPC's line search filter still forbids.
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>

#include "solver/kernels/hd.hpp"
#include "solver/kernels/psd_projection.hpp"

namespace grip::solver::kernels {

using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Vector9d = Eigen::Matrix<double, 9, 1>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;

// Parameters of the stable Neo-Hookean energy, already reparametrized (see the file comment).
struct StableNeoHookeanParameters {
  double mu;      // Pa
  double lambda;  // Pa
};

// Lame parameters from Young's modulus E (Pa) and Poisson ratio nu (-1 < nu < 1/2).
GRIP_HD inline double lame_mu(double youngs_modulus, double poisson_ratio) {
  return youngs_modulus / (2.0 * (1.0 + poisson_ratio));
}
GRIP_HD inline double lame_lambda(double youngs_modulus, double poisson_ratio) {
  return youngs_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
}

// Stable Neo-Hookean parameters that match linear elasticity with (E, nu) at small strain.
GRIP_HD inline StableNeoHookeanParameters stable_neo_hookean_parameters(double youngs_modulus,
                                                                        double poisson_ratio) {
  const double mu = lame_mu(youngs_modulus, poisson_ratio);
  return {mu, lame_lambda(youngs_modulus, poisson_ratio) + mu};
}

// Rest shape matrix Dm = [X1 - X0, X2 - X0, X3 - X0] of a tet (columns are edge vectors).
GRIP_HD inline Eigen::Matrix3d tet_shape_matrix(const Eigen::Vector3d& x0,
                                                const Eigen::Vector3d& x1,
                                                const Eigen::Vector3d& x2,
                                                const Eigen::Vector3d& x3) {
  Eigen::Matrix3d d;
  d.col(0) = x1 - x0;
  d.col(1) = x2 - x0;
  d.col(2) = x3 - x0;
  return d;
}

// Signed rest volume det(Dm) / 6 (positive for a positively oriented tet).
GRIP_HD inline double tet_rest_volume(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                                      const Eigen::Vector3d& x2, const Eigen::Vector3d& x3) {
  return tet_shape_matrix(x0, x1, x2, x3).determinant() / 6.0;
}

// Dm^{-1} of the rest tet, precomputed once per element.
GRIP_HD inline Eigen::Matrix3d tet_rest_shape_inverse(const Eigen::Vector3d& x0,
                                                      const Eigen::Vector3d& x1,
                                                      const Eigen::Vector3d& x2,
                                                      const Eigen::Vector3d& x3) {
  return tet_shape_matrix(x0, x1, x2, x3).inverse();
}

// F = Ds Dm^{-1} from the 12 stacked world coordinates x = (x0, x1, x2, x3).
GRIP_HD inline Eigen::Matrix3d deformation_gradient(const Vector12d& x,
                                                    const Eigen::Matrix3d& rest_shape_inverse) {
  Eigen::Matrix3d ds;
  for (int k = 0; k < 3; ++k) ds.col(k) = x.segment<3>(3 * (k + 1)) - x.segment<3>(0);
  return ds * rest_shape_inverse;
}

// dvec(F)/dx as a 9x12 matrix (vec is column-major: F(i, j) sits at 3 j + i); constant per tet.
GRIP_HD inline Eigen::Matrix<double, 9, 12> deformation_gradient_jacobian(
    const Eigen::Matrix3d& rest_shape_inverse) {
  Eigen::Matrix<double, 9, 12> b = Eigen::Matrix<double, 9, 12>::Zero();
  for (int j = 0; j < 3; ++j) {
    // F(i, j) = sum_k (x_{k+1} - x_0)(i) Dminv(k, j).
    const double sum = rest_shape_inverse.col(j).sum();
    for (int i = 0; i < 3; ++i) {
      b(3 * j + i, i) = -sum;
      for (int k = 0; k < 3; ++k) b(3 * j + i, 3 * (k + 1) + i) = rest_shape_inverse(k, j);
    }
  }
  return b;
}

// dJ/dF, the cofactor matrix of F: columns f1 x f2, f2 x f0, f0 x f1.
GRIP_HD inline Eigen::Matrix3d determinant_gradient(const Eigen::Matrix3d& f) {
  Eigen::Matrix3d g;
  g.col(0) = f.col(1).cross(f.col(2));
  g.col(1) = f.col(2).cross(f.col(0));
  g.col(2) = f.col(0).cross(f.col(1));
  return g;
}

namespace neo_hookean_detail {
// [v]x, the matrix with [v]x w = v x w.
GRIP_HD inline Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}
}  // namespace neo_hookean_detail

// d^2 J / dvec(F)^2: 3x3 blocks (a, b) = d^2 J / df_a df_b, built from cross-product matrices.
GRIP_HD inline Matrix9d determinant_hessian(const Eigen::Matrix3d& f) {
  Matrix9d h = Matrix9d::Zero();
  const Eigen::Matrix3d c0 = neo_hookean_detail::cross_matrix(f.col(0));
  const Eigen::Matrix3d c1 = neo_hookean_detail::cross_matrix(f.col(1));
  const Eigen::Matrix3d c2 = neo_hookean_detail::cross_matrix(f.col(2));
  h.block<3, 3>(0, 3) = -c2;
  h.block<3, 3>(3, 0) = c2;
  h.block<3, 3>(0, 6) = c1;
  h.block<3, 3>(6, 0) = -c1;
  h.block<3, 3>(3, 6) = -c0;
  h.block<3, 3>(6, 3) = c0;
  return h;
}

GRIP_HD inline double stable_neo_hookean_energy_density(const Eigen::Matrix3d& f,
                                                        const StableNeoHookeanParameters& m) {
  const double j = f.determinant();
  return 0.5 * m.mu * (f.squaredNorm() - 3.0) - m.mu * (j - 1.0) +
         0.5 * m.lambda * (j - 1.0) * (j - 1.0);
}

// First Piola-Kirchhoff stress P = dPsi/dF = mu F + (lambda (J - 1) - mu) dJ/dF.
GRIP_HD inline Eigen::Matrix3d stable_neo_hookean_first_piola(const Eigen::Matrix3d& f,
                                                              const StableNeoHookeanParameters& m) {
  const double j = f.determinant();
  return m.mu * f + (m.lambda * (j - 1.0) - m.mu) * determinant_gradient(f);
}

// dP/dF = d^2 Psi / dvec(F)^2 = mu I + lambda g g^T + (lambda (J - 1) - mu) d^2 J/dF^2,
// g = vec(dJ/dF). Indefinite in general (the J terms).
GRIP_HD inline Matrix9d stable_neo_hookean_stress_derivative(const Eigen::Matrix3d& f,
                                                             const StableNeoHookeanParameters& m) {
  const double j = f.determinant();
  const Eigen::Matrix3d cof = determinant_gradient(f);
  const Eigen::Map<const Vector9d> g(cof.data());
  return m.mu * Matrix9d::Identity() + m.lambda * g * g.transpose() +
         (m.lambda * (j - 1.0) - m.mu) * determinant_hessian(f);
}

// F's rotation-variant SVD, F = U diag(s) V^T with U and V rotations and s[2] < 0 when the tet
// is inverted (det F < 0), in closed form rather than by Jacobi sweeps: V the eigenvectors of
// F^T F (Eigen's computeDirect; largest first, made orthonormal), U's first two columns F v / s
// made orthonormal, the third their cross product, and s[2] = u2 . F v2, which carries det F's
// sign. Where singular values (nearly) repeat, as at rest, computeDirect's eigenvectors are
// orthogonal to about 1e-9 only, and U diag(s) V^T is F to about 1e-9 of |F|: a projection
// built on it moves by that fraction of the eigenvalue it removes, far below anything Newton's
// tolerance sees. computeDirect is closed form and device-callable, unlike Eigen's iterative
// solver (psd_projection.hpp), so this runs on both launchers.
struct RotationVariantSvd {
  Eigen::Matrix3d u;
  Eigen::Matrix3d v;
  Eigen::Vector3d s;
};

GRIP_HD inline RotationVariantSvd rotation_variant_svd(const Eigen::Matrix3d& f) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> gram;
  gram.computeDirect(f.transpose() * f);
  RotationVariantSvd svd;
  // Eigenvalues come in increasing order: the largest's vector first.
  svd.v.col(0) = gram.eigenvectors().col(2).normalized();
  const Eigen::Vector3d second = gram.eigenvectors().col(1);
  svd.v.col(1) = (second - svd.v.col(0).dot(second) * svd.v.col(0)).normalized();
  svd.v.col(2) = svd.v.col(0).cross(svd.v.col(1));
  // A column of U whose F v vanishes (a flat or collapsed tet) may be any unit vector
  // orthogonal to the ones before it.
  const auto any_orthogonal = [](const Eigen::Vector3d& a) -> Eigen::Vector3d {
    const Eigen::Vector3d axis =
        std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    return a.cross(axis).normalized();
  };
  const Eigen::Vector3d u0 = f * svd.v.col(0);
  svd.s[0] = u0.norm();
  svd.u.col(0) = svd.s[0] > 0.0 ? Eigen::Vector3d(u0 / svd.s[0]) : Eigen::Vector3d::UnitX();
  Eigen::Vector3d u1 = f * svd.v.col(1);
  u1 -= svd.u.col(0).dot(u1) * svd.u.col(0);
  const double length = u1.norm();
  svd.u.col(1) = length > 1e-12 * svd.s[0] && length > 0.0 ? Eigen::Vector3d(u1 / length)
                                                           : any_orthogonal(svd.u.col(0));
  svd.s[1] = svd.u.col(1).dot(f * svd.v.col(1));
  svd.u.col(2) = svd.u.col(0).cross(svd.u.col(1));
  svd.s[2] = svd.u.col(2).dot(f * svd.v.col(2));
  return svd;
}

// dP/dF projected to the nearest PSD matrix from its analytic eigensystem (Smith et al. 2019,
// "Analytic Eigensystems for Isotropic Distortion Energies"), not a numeric 9x9 decomposition.
// With F = U diag(s) V^T (U, V rotations; s2 < 0 when the tet is inverted) and
// c = lambda (J - 1) - mu, dP/dF = mu I + lambda g g^T + c d^2J/dF^2 has
//   twists U [e_k]x V^T / sqrt(2):             eigenvalue mu + c s_k,
//   flips (the same with symmetric [e_k]x):    eigenvalue mu - c s_k,
//   scalings U diag(a) V^T, a an eigenvector of the 3x3 matrix
//     mu I + lambda g_s g_s^T + c [[0, s2, s1], [s2, 0, s0], [s1, s0, 0]],  g_s = (s1 s2, s0 s2, s0
//     s1).
// The negative modes are removed from the exact dP/dF, so a PSD one is returned unchanged.
// No Cholesky test first: the twists' eigenvalues are zero at rest (rotations), and almost any
// strain that is not a pure dilation makes one slightly negative, so such a test fails for most
// tets of a deformed body and only adds its cost.
GRIP_HD inline Matrix9d stable_neo_hookean_stress_derivative_psd(
    const Eigen::Matrix3d& f, const StableNeoHookeanParameters& m) {
  Matrix9d dpdf = stable_neo_hookean_stress_derivative(f, m);
  const RotationVariantSvd svd = rotation_variant_svd(f);
  const Eigen::Vector3d& s = svd.s;
  const double c = m.lambda * (s.prod() - 1.0) - m.mu;
  // Removes the mode U a V^T (a unit in the Frobenius norm) with eigenvalue `value` if negative.
  const auto remove_if_negative = [&](double value, const Eigen::Matrix3d& a) {
    if (value >= 0.0) return;
    const Eigen::Matrix3d mode = svd.u * a * svd.v.transpose();
    const Eigen::Map<const Vector9d> e(mode.data());
    dpdf -= value * e * e.transpose();
  };
  const double half = std::sqrt(0.5);
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    Eigen::Matrix3d twist = Eigen::Matrix3d::Zero(), flip = Eigen::Matrix3d::Zero();
    twist(i, j) = -half;
    twist(j, i) = half;
    flip(i, j) = flip(j, i) = half;
    remove_if_negative(m.mu + c * s[k], twist);
    remove_if_negative(m.mu - c * s[k], flip);
  }
  const Eigen::Vector3d g(s[1] * s[2], s[0] * s[2], s[0] * s[1]);
  Eigen::Matrix3d scaling = m.mu * Eigen::Matrix3d::Identity() + m.lambda * g * g.transpose();
  scaling(0, 1) += c * s[2];
  scaling(0, 2) += c * s[1];
  scaling(1, 2) += c * s[0];
  scaling(1, 0) = scaling(0, 1);
  scaling(2, 0) = scaling(0, 2);
  scaling(2, 1) = scaling(1, 2);
  // Positive leading minors (Sylvester): no negative scaling, and no eigensolve, as for most
  // tets (about 2 mu I + (lambda - mu) 11^T near rest).
  const double minor2 = scaling(0, 0) * scaling(1, 1) - scaling(0, 1) * scaling(0, 1);
  if (scaling(0, 0) > 0.0 && minor2 > 0.0 && scaling.determinant() > 0.0) return dpdf;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> modes;
  modes.computeDirect(scaling);
  for (int k = 0; k < 3; ++k) {
    // Written out: Eigen 3.4 turns a DiagonalWrapper into a dense matrix by host-only code.
    Eigen::Matrix3d scaling_mode = Eigen::Matrix3d::Zero();
    for (int i = 0; i < 3; ++i) scaling_mode(i, i) = modes.eigenvectors()(i, k);
    remove_if_negative(modes.eigenvalues()[k], scaling_mode);
  }
  return dpdf;
}

// Elastic energy of a tet: rest volume times the energy density.
GRIP_HD inline double tet_stable_neo_hookean_energy(const Vector12d& x,
                                                    const Eigen::Matrix3d& rest_shape_inverse,
                                                    double rest_volume,
                                                    const StableNeoHookeanParameters& m) {
  return rest_volume *
         stable_neo_hookean_energy_density(deformation_gradient(x, rest_shape_inverse), m);
}

// D, the 4x3 matrix of the shape functions' gradients: row 0 minus the sum of Dm^{-1}'s rows,
// then Dm^{-1}. F = sum_a x_a D(a, :), so B = dvec(F)/dx has the 3x3 blocks
// B(3j + i, 3a + i) = D(a, j).
GRIP_HD inline Eigen::Matrix<double, 4, 3> shape_function_gradients(
    const Eigen::Matrix3d& rest_shape_inverse) {
  Eigen::Matrix<double, 4, 3> d;
  d.row(0) = -rest_shape_inverse.colwise().sum();
  d.bottomRows<3>() = rest_shape_inverse;
  return d;
}

// d energy / dx = V B^T vec(P) at the deformation gradient f, summed by B's blocks: vertex a's
// 3-vector is V P D(a, :)^T.
GRIP_HD inline Vector12d tet_stable_neo_hookean_gradient(const Eigen::Matrix3d& f,
                                                         const Eigen::Matrix3d& rest_shape_inverse,
                                                         double rest_volume,
                                                         const StableNeoHookeanParameters& m) {
  const Eigen::Matrix<double, 3, 4> g = (rest_volume * stable_neo_hookean_first_piola(f, m)) *
                                        shape_function_gradients(rest_shape_inverse).transpose();
  return Eigen::Map<const Vector12d>(g.data());
}

GRIP_HD inline Vector12d tet_stable_neo_hookean_gradient(const Vector12d& x,
                                                         const Eigen::Matrix3d& rest_shape_inverse,
                                                         double rest_volume,
                                                         const StableNeoHookeanParameters& m) {
  return tet_stable_neo_hookean_gradient(deformation_gradient(x, rest_shape_inverse),
                                         rest_shape_inverse, rest_volume, m);
}

// B^T A B for a 9x9 A and B = dvec(F)/dx: B's 3x3 blocks are multiples of the identity,
// B(3j + i, 3a + i) = D(a, j) (shape_function_gradients), so the product is summed block by block
// at about a third of a dense product's multiplications.
GRIP_HD inline Matrix12d deformation_gradient_congruence(const Eigen::Matrix3d& rest_shape_inverse,
                                                         const Matrix9d& a) {
  const Eigen::Matrix<double, 4, 3> d = shape_function_gradients(rest_shape_inverse);
  // A B, one 9x3 block column per vertex.
  Eigen::Matrix<double, 9, 12> ab;
  for (int v = 0; v < 4; ++v) {
    ab.middleCols<3>(3 * v) =
        a.middleCols<3>(0) * d(v, 0) + a.middleCols<3>(3) * d(v, 1) + a.middleCols<3>(6) * d(v, 2);
  }
  Matrix12d h;
  for (int u = 0; u < 4; ++u) {
    h.middleRows<3>(3 * u) = d(u, 0) * ab.middleRows<3>(0) + d(u, 1) * ab.middleRows<3>(3) +
                             d(u, 2) * ab.middleRows<3>(6);
  }
  return h;
}

// d^2 energy / dx^2 = V B^T (dP/dF) B. With project_psd, dP/dF is replaced by its nearest
// positive semi-definite matrix (negative eigenvalues clamped to zero), as projected Newton
// needs. B (9 x 12) has full rank 9, so the 12x12 Hessian is PSD exactly when the 9x9 dP/dF
// is: projecting the smaller matrix gives a PSD Hessian, leaves a PSD one unchanged, and
// costs less than half as much.
GRIP_HD inline Matrix12d tet_stable_neo_hookean_hessian(const Eigen::Matrix3d& f,
                                                        const Eigen::Matrix3d& rest_shape_inverse,
                                                        double rest_volume,
                                                        const StableNeoHookeanParameters& m,
                                                        bool project_psd) {
  const Matrix9d dpdf = project_psd ? stable_neo_hookean_stress_derivative_psd(f, m)
                                    : stable_neo_hookean_stress_derivative(f, m);
  return rest_volume * deformation_gradient_congruence(rest_shape_inverse, dpdf);
}

GRIP_HD inline Matrix12d tet_stable_neo_hookean_hessian(const Vector12d& x,
                                                        const Eigen::Matrix3d& rest_shape_inverse,
                                                        double rest_volume,
                                                        const StableNeoHookeanParameters& m,
                                                        bool project_psd) {
  return tet_stable_neo_hookean_hessian(deformation_gradient(x, rest_shape_inverse),
                                        rest_shape_inverse, rest_volume, m, project_psd);
}

// Cauchy stress sigma = P F^T / J = (mu F F^T + (lambda (J - 1) - mu) J I) / J (Pa, symmetric);
// undefined for J = 0.
GRIP_HD inline Eigen::Matrix3d stable_neo_hookean_cauchy_stress(
    const Eigen::Matrix3d& f, const StableNeoHookeanParameters& m) {
  return stable_neo_hookean_first_piola(f, m) * f.transpose() / f.determinant();
}

// Von Mises equivalent stress sqrt(3/2 s:s) of a Cauchy stress, s its deviatoric part (Pa).
GRIP_HD inline double von_mises_stress(const Eigen::Matrix3d& cauchy_stress) {
  const Eigen::Matrix3d dev =
      cauchy_stress - cauchy_stress.trace() / 3.0 * Eigen::Matrix3d::Identity();
  return std::sqrt(1.5 * dev.squaredNorm());
}

}  // namespace grip::solver::kernels
