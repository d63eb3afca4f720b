// Stable Neo-Hookean tet kernels: analytic values at rest and at small strain, rotation
// invariance, derivatives against central differences on random (including nearly flat,
// compressed and largely rotated) tets, PSD projection and the von Mises stress.
#include "solver/kernels/neo_hookean.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <ostream>
#include <random>
#include <string>

#include "tests/kernels/finite_difference.hpp"

namespace {

using namespace grip::solver::kernels;
using grip::test::fd_gradient;
using grip::test::fd_jacobian;
using grip::test::relatively_close;

constexpr double kYoungs = 9.4e6;  // Pa, the UMI fingers' modulus
constexpr double kPoisson = 0.45;

Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

// A rest tet with edges of length ~scale and a quality bounded away from flat.
struct RestTet {
  Eigen::Vector3d x[4];
  Eigen::Matrix3d dm_inv;
  double volume;
};

RestTet random_rest_tet(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  RestTet tet;
  const Eigen::Matrix3d r = random_rotation(rng);
  const Eigen::Vector3d offset(u(rng), u(rng), u(rng));
  const Eigen::Vector3d corners[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int i = 0; i < 4; ++i) {
    tet.x[i] = scale * (r * (corners[i] + Eigen::Vector3d(u(rng), u(rng), u(rng))) + offset);
  }
  tet.volume = tet_rest_volume(tet.x[0], tet.x[1], tet.x[2], tet.x[3]);
  if (tet.volume < 0) std::swap(tet.x[1], tet.x[2]);
  tet.volume = tet_rest_volume(tet.x[0], tet.x[1], tet.x[2], tet.x[3]);
  tet.dm_inv = tet_rest_shape_inverse(tet.x[0], tet.x[1], tet.x[2], tet.x[3]);
  return tet;
}

// The kinds of deformation the derivative checks sweep.
enum class Deformation { kGeneric, kNearlyFlat, kCompressed, kLargeRotation };

// World positions x = F_target X + c of a rest tet; F_target is chosen per kind so that
// det F > 0 (small for nearly flat tets).
Vector12d deform(const RestTet& tet, Deformation kind, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
  switch (kind) {
    case Deformation::kGeneric:
      for (int i = 0; i < 9; ++i) f(i) += 0.3 * u(rng);
      break;
    case Deformation::kNearlyFlat: {
      // Squash along a random direction to 1e-3..1e-2 of its length: det F in (1e-3, 1e-2].
      const Eigen::Matrix3d r = random_rotation(rng);
      const double squash = std::pow(10.0, -2.5 + 0.5 * u(rng));
      f = r * Eigen::Vector3d(1.0 + 0.2 * u(rng), 1.0 + 0.2 * u(rng), squash).asDiagonal() *
          r.transpose();
      break;
    }
    case Deformation::kCompressed:
      f = (0.3 + 0.1 * u(rng)) * Eigen::Matrix3d::Identity();
      for (int i = 0; i < 9; ++i) f(i) += 0.05 * u(rng);
      break;
    case Deformation::kLargeRotation:
      f = random_rotation(rng);
      for (int i = 0; i < 9; ++i) f(i) += 0.2 * u(rng);
      break;
  }
  const Eigen::Vector3d c(u(rng), u(rng), u(rng));
  Vector12d x;
  for (int i = 0; i < 4; ++i) x.segment<3>(3 * i) = f * tet.x[i] + c;
  return x;
}

TEST(NeoHookean, LameParametersMatchTheirDefinition) {
  // E = 2 mu (1 + nu), nu = lambda / (2 (lambda + mu)).
  const double mu = lame_mu(kYoungs, kPoisson);
  const double lambda = lame_lambda(kYoungs, kPoisson);
  EXPECT_NEAR(2.0 * mu * (1.0 + kPoisson), kYoungs, 1e-9 * kYoungs);
  EXPECT_NEAR(lambda / (2.0 * (lambda + mu)), kPoisson, 1e-12);
  const StableNeoHookeanParameters m = stable_neo_hookean_parameters(kYoungs, kPoisson);
  EXPECT_DOUBLE_EQ(m.mu, mu);
  EXPECT_DOUBLE_EQ(m.lambda, lambda + mu);
}

TEST(NeoHookean, SmallStrainMatchesLinearElasticity) {
  // Psi(I + delta S) = delta^2 (mu_L S:S + lambda_L/2 tr(S)^2) + O(delta^3) for symmetric S.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const StableNeoHookeanParameters m = stable_neo_hookean_parameters(kYoungs, kPoisson);
  const double mu_l = lame_mu(kYoungs, kPoisson);
  const double lambda_l = lame_lambda(kYoungs, kPoisson);
  for (int trial = 0; trial < 100; ++trial) {
    Eigen::Matrix3d s;
    for (int i = 0; i < 9; ++i) s(i) = u(rng);
    s = 0.5 * (s + s.transpose()).eval();
    const double linear = mu_l * s.squaredNorm() + 0.5 * lambda_l * s.trace() * s.trace();
    const double delta = 1e-5;
    const Eigen::Matrix3d f = Eigen::Matrix3d::Identity() + delta * s;
    EXPECT_NEAR(stable_neo_hookean_energy_density(f, m) / (delta * delta), linear, 1e-3 * linear);
  }
}

TEST(NeoHookean, RestIsEnergyAndStressFree) {
  std::mt19937_64 rng(11);
  const StableNeoHookeanParameters m = stable_neo_hookean_parameters(kYoungs, kPoisson);
  EXPECT_EQ(stable_neo_hookean_energy_density(Eigen::Matrix3d::Identity(), m), 0.0);
  EXPECT_EQ(stable_neo_hookean_first_piola(Eigen::Matrix3d::Identity(), m).norm(), 0.0);
  for (int trial = 0; trial < 200; ++trial) {
    const RestTet tet = random_rest_tet(rng, 1e-2);
    // Rest pose moved rigidly: F is a rotation, so energy and forces vanish.
    const Eigen::Matrix3d r = random_rotation(rng);
    const Eigen::Vector3d c = Eigen::Vector3d::Random();
    Vector12d x;
    for (int i = 0; i < 4; ++i) x.segment<3>(3 * i) = r * tet.x[i] + c;
    const Eigen::Matrix3d f = deformation_gradient(x, tet.dm_inv);
    EXPECT_LT((f.transpose() * f - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    const double force_scale = m.mu * tet.volume / 1e-2;  // stress x area
    EXPECT_LT(std::abs(tet_stable_neo_hookean_energy(x, tet.dm_inv, tet.volume, m)),
              1e-12 * m.mu * tet.volume);
    EXPECT_LT(tet_stable_neo_hookean_gradient(x, tet.dm_inv, tet.volume, m).norm(),
              1e-10 * force_scale);
    EXPECT_LT(von_mises_stress(stable_neo_hookean_cauchy_stress(f, m)), 1e-9 * m.mu);
  }
}

TEST(NeoHookean, EnergyIsRotationInvariant) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const StableNeoHookeanParameters m = stable_neo_hookean_parameters(kYoungs, kPoisson);
  for (int trial = 0; trial < 1000; ++trial) {
    Eigen::Matrix3d f;
    for (int i = 0; i < 9; ++i) f(i) = u(rng);
    const double psi = stable_neo_hookean_energy_density(f, m);
    const double rotated = stable_neo_hookean_energy_density(random_rotation(rng) * f, m);
    EXPECT_NEAR(rotated, psi, 1e-12 * (std::abs(psi) + m.mu + m.lambda));
  }
}

TEST(NeoHookean, DensityDerivativesMatchCentralDifferences) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const StableNeoHookeanParameters m = stable_neo_hookean_parameters(kYoungs, kPoisson);
  for (int trial = 0; trial < 2000; ++trial) {
    Eigen::Matrix3d f0;
    for (int i = 0; i < 9; ++i) f0(i) = (trial % 2 ? 2.0 : 0.5) * u(rng);
    const Vector9d vf(f0.data());
    auto psi = [&](const Vector9d& v) {
      return stable_neo_hookean_energy_density(Eigen::Map<const Eigen::Matrix3d>(v.data()), m);
    };
    auto piola = [&](const Vector9d& v) -> Vector9d {
      const Eigen::Matrix3d p =
          stable_neo_hookean_first_piola(Eigen::Map<const Eigen::Matrix3d>(v.data()), m);
      return Vector9d(p.data());
    };
    const Eigen::Matrix3d p = stable_neo_hookean_first_piola(f0, m);
    const double h = 1e-6 * (1.0 + f0.norm());
    const double stress = m.mu + m.lambda;
    ASSERT_TRUE(
        relatively_close(Vector9d(p.data()), fd_gradient<9>(vf, psi, h), 1e-6, 1e-6 * stress));
    ASSERT_TRUE(relatively_close(stable_neo_hookean_stress_derivative(f0, m),
                                 fd_jacobian<9, 9>(vf, piola, h), 1e-6, 1e-6 * stress));
  }
}

struct TetCase {
  Deformation kind;
  double scale;  // rest edge length (m)
};

void PrintTo(const TetCase& c, std::ostream* out) {
  *out << "deformation " << static_cast<int>(c.kind) << ", rest edge " << c.scale << " m";
}

class TetDerivatives : public ::testing::TestWithParam<TetCase> {};

TEST_P(TetDerivatives, GradientAndHessianMatchCentralDifferences) {
  const TetCase c = GetParam();
  std::mt19937_64 rng(19 + static_cast<int>(c.kind));
  const StableNeoHookeanParameters m = stable_neo_hookean_parameters(kYoungs, kPoisson);
  for (int trial = 0; trial < 500; ++trial) {
    const RestTet tet = random_rest_tet(rng, c.scale);
    const Vector12d x = deform(tet, c.kind, rng);
    ASSERT_GT(deformation_gradient(x, tet.dm_inv).determinant(), 0.0);
    auto energy = [&](const Vector12d& v) {
      return tet_stable_neo_hookean_energy(v, tet.dm_inv, tet.volume, m);
    };
    auto gradient = [&](const Vector12d& v) {
      return tet_stable_neo_hookean_gradient(v, tet.dm_inv, tet.volume, m);
    };
    const double h = 1e-7 * c.scale;
    // Forces ~ stress x area, stiffness ~ stress x length: the floors for "zero".
    const double force = (m.mu + m.lambda) * c.scale * c.scale;
    const double stiffness = (m.mu + m.lambda) * c.scale;
    ASSERT_TRUE(relatively_close(gradient(x), fd_gradient<12>(x, energy, h), 1e-5, 1e-7 * force))
        << "trial " << trial;
    ASSERT_TRUE(
        relatively_close(tet_stable_neo_hookean_hessian(x, tet.dm_inv, tet.volume, m, false),
                         fd_jacobian<12, 12>(x, gradient, h), 1e-6, 1e-7 * stiffness))
        << "trial " << trial;
  }
}

std::string tet_case_name(const ::testing::TestParamInfo<TetCase>& info) {
  static const char* const kNames[] = {"Generic", "NearlyFlat", "Compressed", "LargeRotation"};
  return std::string(kNames[static_cast<int>(info.param.kind)]) + (info.param.scale < 1e-2  ? "Mm"
                                                                   : info.param.scale < 1.0 ? "Cm"
                                                                                            : "M");
}

INSTANTIATE_TEST_SUITE_P(Deformations, TetDerivatives,
                         ::testing::Values(TetCase{Deformation::kGeneric, 1.0},
                                           TetCase{Deformation::kGeneric, 1e-3},
                                           TetCase{Deformation::kNearlyFlat, 1e-2},
                                           TetCase{Deformation::kCompressed, 1e-2},
                                           TetCase{Deformation::kLargeRotation, 1e-2}),
                         tet_case_name);

TEST(NeoHookean, ProjectedHessianIsPsdAndUnchangedWhenAlreadyPsd) {
  std::mt19937_64 rng(23);
  const StableNeoHookeanParameters m = stable_neo_hookean_parameters(kYoungs, kPoisson);
  int indefinite = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const RestTet tet = random_rest_tet(rng, 1e-2);
    const Vector12d x =
        deform(tet, trial % 2 ? Deformation::kCompressed : Deformation::kGeneric, rng);
    const Matrix12d h = tet_stable_neo_hookean_hessian(x, tet.dm_inv, tet.volume, m, false);
    const Matrix12d p = tet_stable_neo_hookean_hessian(x, tet.dm_inv, tet.volume, m, true);
    const Eigen::SelfAdjointEigenSolver<Matrix12d> before(h);
    const Eigen::SelfAdjointEigenSolver<Matrix12d> after(p);
    const double tol = 1e-12 * h.norm();
    EXPECT_GE(after.eigenvalues().minCoeff(), -tol);
    if (before.eigenvalues().minCoeff() < -tol) {
      ++indefinite;
    } else {
      EXPECT_LT((p - h).norm(), 1e-10 * h.norm());
    }
  }
  // Strong compression makes the stable Neo-Hookean Hessian indefinite: the projection is used.
  EXPECT_GT(indefinite, 100);

  // At rest the Hessian is PSD already and the projection must leave it as it is.
  const RestTet tet = random_rest_tet(rng, 1e-2);
  Vector12d rest;
  for (int i = 0; i < 4; ++i) rest.segment<3>(3 * i) = tet.x[i];
  const Matrix12d h = tet_stable_neo_hookean_hessian(rest, tet.dm_inv, tet.volume, m, false);
  EXPECT_LT((tet_stable_neo_hookean_hessian(rest, tet.dm_inv, tet.volume, m, true) - h).norm(),
            1e-10 * h.norm());
}

// The analytic eigensystem's projection equals the numeric one (9x9 eigen-decomposition) for
// stretched, compressed, nearly flat and inverted deformation gradients, and leaves a positive
// definite dP/dF bit for bit as it is.
TEST(NeoHookean, AnalyticProjectionMatchesTheNumericOne) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int indefinite = 0, inverted = 0;
  for (const double poisson : {0.3, 0.45, 0.49}) {
    const StableNeoHookeanParameters m = stable_neo_hookean_parameters(kYoungs, poisson);
    for (int trial = 0; trial < 1000; ++trial) {
      // A random rotation times stretches in (0.05, 2) times a random rotation; a quarter of
      // them reflected (inverted tets), some with one stretch near zero (nearly flat).
      const auto rotation = [&] {
        return Eigen::Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng))
            .normalized()
            .toRotationMatrix();
      };
      const Eigen::Matrix3d r1 = rotation(), r2 = rotation();
      Eigen::Vector3d s(1.0 + 0.95 * unit(rng), 1.0 + 0.95 * unit(rng), 1.0 + 0.95 * unit(rng));
      if (trial % 7 == 0) s[trial % 3] = 1e-4;
      if (trial % 4 == 0) {
        s[1] = -s[1];
        ++inverted;
      }
      const Eigen::Matrix3d f = r1 * s.asDiagonal() * r2;
      const Matrix9d exact = stable_neo_hookean_stress_derivative(f, m);
      const Matrix9d analytic = stable_neo_hookean_stress_derivative_psd(f, m);
      const Matrix9d numeric = project_to_psd<9>(exact);
      EXPECT_LT((analytic - numeric).norm(), 1e-9 * exact.norm()) << "F =\n" << f;
      if (Eigen::LLT<Matrix9d>(exact).info() == Eigen::Success) {
        EXPECT_EQ(analytic, exact);
      } else {
        ++indefinite;
      }
    }
  }
  EXPECT_GT(indefinite, 1000);
  EXPECT_GT(inverted, 500);
}

// The closed-form rotation-variant SVD: U and V rotations to rounding, U diag(s) V^T = F to
// 1e-12 of |F| where the singular values are apart and 1e-8 where they (nearly) repeat (at
// rest, measured up to 1.5e-9), and s[2] negative exactly for inverted F; also for nearly zero
// and zero singular values (flat and collapsed tets).
TEST(NeoHookean, RotationVariantSvdReconstructsFWithRotations) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto rotation = [&] {
    return Eigen::Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng))
        .normalized()
        .toRotationMatrix();
  };
  struct Case {
    Eigen::Matrix3d f;
    bool repeated;
  };
  std::vector<Case> cases = {{Eigen::Matrix3d::Identity(), true},
                             {Eigen::Matrix3d::Zero(), true},
                             {rotation(), true},
                             {2.0 * rotation(), true}};
  for (int trial = 0; trial < 2000; ++trial) {
    Eigen::Vector3d s(1.0 + 0.95 * unit(rng), 1.0 + 0.95 * unit(rng), 1.0 + 0.95 * unit(rng));
    bool repeated = false;
    if (trial % 5 == 0) {
      s[1] = s[0];
      repeated = true;
    }
    if (trial % 7 == 0) s[trial % 3] = 1e-4;  // nearly flat
    if (trial % 11 == 0) s[trial % 3] = 0.0;  // flat
    if (trial % 13 == 0) {                    // near rest
      s = Eigen::Vector3d::Constant(1.0 + 1e-9 * unit(rng));
      repeated = true;
    }
    if (trial % 4 == 0) s[2] = -s[2];  // inverted
    const Eigen::Vector3d sorted = s.cwiseAbs();
    repeated = repeated || std::abs(sorted[0] - sorted[1]) < 1e-3 ||
               std::abs(sorted[1] - sorted[2]) < 1e-3 || std::abs(sorted[0] - sorted[2]) < 1e-3;
    cases.push_back({rotation() * s.asDiagonal() * rotation(), repeated});
  }
  for (const Case& c : cases) {
    const Eigen::Matrix3d& f = c.f;
    const RotationVariantSvd svd = rotation_variant_svd(f);
    const double scale = std::max(1.0, f.norm());
    EXPECT_LT((svd.u * svd.s.asDiagonal() * svd.v.transpose() - f).norm(),
              (c.repeated ? 1e-8 : 1e-12) * scale)
        << "F =\n"
        << f;
    EXPECT_LT((svd.u.transpose() * svd.u - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_LT((svd.v.transpose() * svd.v - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(svd.u.determinant(), 1.0, 1e-12);
    EXPECT_NEAR(svd.v.determinant(), 1.0, 1e-12);
    if (f.determinant() < -1e-12) {
      EXPECT_LT(svd.s[2], 0.0) << "F =\n" << f;
    }
    if (f.determinant() > 1e-12) {
      EXPECT_GT(svd.s.minCoeff(), 0.0) << "F =\n" << f;
    }
  }
}

// The block-wise B^T A B of the tet Hessian equals the dense product to rounding, for any
// (not only symmetric) 9x9 A.
TEST(NeoHookean, BlockwiseCongruenceMatchesTheDenseProduct) {
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const RestTet tet = random_rest_tet(rng, trial % 2 ? 1e-2 : 1e-3);
    Matrix9d a;
    for (int i = 0; i < 81; ++i) a(i) = 1e6 * unit(rng);
    const Eigen::Matrix<double, 9, 12> b = deformation_gradient_jacobian(tet.dm_inv);
    const Matrix12d dense = b.transpose() * a * b;
    EXPECT_LT((deformation_gradient_congruence(tet.dm_inv, a) - dense).norm(),
              1e-13 * dense.norm());
  }
}

// The tet gradient summed by B's blocks (V P D^T) equals the dense V B^T vec(P) to rounding, at
// rest-sized and at stretched, sheared and inverted deformations.
TEST(NeoHookean, BlockwiseGradientMatchesTheDenseProduct) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const StableNeoHookeanParameters m = stable_neo_hookean_parameters(1e6, 0.45);
  for (int trial = 0; trial < 200; ++trial) {
    const RestTet tet = random_rest_tet(rng, trial % 2 ? 1e-2 : 1e-3);
    Eigen::Matrix3d f;
    for (int i = 0; i < 9; ++i) f(i) = unit(rng);
    f += Eigen::Matrix3d::Identity() * (trial % 3 == 0 ? -0.5 : 1.0);
    const Eigen::Matrix3d p = stable_neo_hookean_first_piola(f, m);
    const Vector12d dense = tet.volume * deformation_gradient_jacobian(tet.dm_inv).transpose() *
                            Eigen::Map<const Vector9d>(p.data());
    EXPECT_LT((tet_stable_neo_hookean_gradient(f, tet.dm_inv, tet.volume, m) - dense).norm(),
              1e-13 * dense.norm());
  }
}

TEST(NeoHookean, VonMisesOfKnownStressStates) {
  // Uniaxial sigma: |sigma|; pure shear tau: sqrt(3) tau; hydrostatic: 0.
  const double s = 1.5e6;
  EXPECT_NEAR(von_mises_stress(Eigen::Vector3d(s, 0, 0).asDiagonal().toDenseMatrix()), s, 1e-9 * s);
  Eigen::Matrix3d shear = Eigen::Matrix3d::Zero();
  shear(0, 1) = shear(1, 0) = s;
  EXPECT_NEAR(von_mises_stress(shear), std::sqrt(3.0) * s, 1e-9 * s);
  EXPECT_NEAR(von_mises_stress(-s * Eigen::Matrix3d::Identity()), 0.0, 1e-9 * s);

  // A uniform dilation of a Neo-Hookean solid is a hydrostatic state: zero von Mises stress,
  // pressure sigma = (mu a^2 + (lambda (a^3 - 1) - mu) a^3) / a^3.
  const StableNeoHookeanParameters m = stable_neo_hookean_parameters(kYoungs, kPoisson);
  const double a = 1.1;
  const Eigen::Matrix3d sigma =
      stable_neo_hookean_cauchy_stress(a * Eigen::Matrix3d::Identity(), m);
  const double j = a * a * a;
  EXPECT_NEAR(sigma(0, 0), (m.mu * a * a + (m.lambda * (j - 1) - m.mu) * j) / j, 1e-9 * m.lambda);
  EXPECT_LT(von_mises_stress(sigma), 1e-9 * m.lambda);

  // Simple stretch along x with lateral sides fixed (F = diag(a, 1, 1)): Cauchy stress
  // diag(mu a + (lambda (a - 1) - mu), lambda (a - 1) - mu + mu / a, same), so von Mises is
  // the difference of the axial and lateral components.
  const Eigen::Matrix3d stretch = Eigen::Vector3d(a, 1, 1).asDiagonal();
  const double axial = m.mu * a + m.lambda * (a - 1) - m.mu;
  const double lateral = m.lambda * (a - 1) - m.mu + m.mu / a;
  EXPECT_NEAR(von_mises_stress(stable_neo_hookean_cauchy_stress(stretch, m)),
              std::abs(axial - lateral), 1e-9 * m.lambda);
}

}  // namespace
