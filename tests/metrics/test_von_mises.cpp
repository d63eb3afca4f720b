#include "src/metrics/von_mises.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

#include "src/scene/primitives.hpp"

namespace grip::metrics {
namespace {

constexpr double kYoungs = 2e6;
constexpr double kPoisson = 0.3;
const double kMu = kYoungs / (2.0 * (1.0 + kPoisson));  // the shear modulus

geometry::TetMesh block() { return scene::box_tets(Eigen::Vector3d(0.02, 0.03, 0.04), 0.01); }

geometry::Vertices deform(const geometry::Vertices& rest, const Eigen::Matrix3d& f) {
  return rest * f.transpose();
}

TEST(VonMises, ZeroAtRestAndUnderRigidMotion) {
  const geometry::TetMesh mesh = block();
  EXPECT_LT(von_mises_stress(mesh, mesh.vertices, kYoungs, kPoisson).maxCoeff(), 1e-9);
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const geometry::Vertices moved =
      (deform(mesh.vertices, r).rowwise() + Eigen::RowVector3d(1, 2, 3));
  EXPECT_LT(von_mises_stress(mesh, moved, kYoungs, kPoisson).maxCoeff(), 1e-6);
}

TEST(VonMises, UniaxialStretchMatchesTheAnalyticValue) {
  // F = diag(l, 1, 1): sigma = (mu F F^T + (lambda (J - 1) - mu) J I) / J with J = l, whose
  // deviator gives von Mises = |sigma_11 - sigma_22| = mu (l^2 - 1) / l, uniform over the tets.
  const geometry::TetMesh mesh = block();
  for (double l : {0.8, 1.05, 1.3}) {
    const Eigen::Vector3d stretch(l, 1.0, 1.0);
    const Eigen::VectorXd s =
        von_mises_stress(mesh, deform(mesh.vertices, stretch.asDiagonal()), kYoungs, kPoisson);
    const double expected = kMu * std::abs(l * l - 1.0) / l;
    EXPECT_NEAR(s.minCoeff(), expected, 1e-9 * expected);
    EXPECT_NEAR(s.maxCoeff(), expected, 1e-9 * expected);
  }
}

TEST(VonMises, SimpleShearMatchesTheAnalyticValueAndIgnoresRotation) {
  // F = I + g e1 e2^T (J = 1): von Mises of mu F F^T is mu g sqrt(3 + g^2).
  const geometry::TetMesh mesh = block();
  const double g = 0.2;
  Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
  f(0, 1) = g;
  const double expected = kMu * g * std::sqrt(3.0 + g * g);
  const Eigen::VectorXd s = von_mises_stress(mesh, deform(mesh.vertices, f), kYoungs, kPoisson);
  EXPECT_NEAR(s.maxCoeff(), expected, 1e-9 * expected);
  EXPECT_NEAR(s.minCoeff(), expected, 1e-9 * expected);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::VectorXd turned =
      von_mises_stress(mesh, deform(mesh.vertices, r * f), kYoungs, kPoisson);
  EXPECT_LT((turned - s).cwiseAbs().maxCoeff(), 1e-9 * expected);
}

TEST(VonMises, RejectsMismatchedAndInvertedMeshes) {
  const geometry::TetMesh mesh = block();
  EXPECT_THROW(von_mises_stress(mesh, mesh.vertices.topRows(3), kYoungs, kPoisson),
               std::invalid_argument);
  const Eigen::Vector3d mirror(-1.0, 1.0, 1.0);
  EXPECT_THROW(
      von_mises_stress(mesh, deform(mesh.vertices, mirror.asDiagonal()), kYoungs, kPoisson),
      std::invalid_argument);
}

}  // namespace
}  // namespace grip::metrics
