// The contact patch's rigid motion: exact for a rigidly moved patch, its mean's translation for
// a patch that cannot determine a turn, and weighted by the contact forces.
#include "src/trial/contact_patch.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace grip::trial {
namespace {

solver::Vertices moved(const solver::Vertices& x, const RigidMotion& m) {
  solver::Vertices y(x.rows(), 3);
  for (int v = 0; v < x.rows(); ++v) y.row(v) = m(x.row(v).transpose()).transpose();
  return y;
}

RigidMotion some_motion() {
  RigidMotion m;
  m.rotation = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).matrix();
  m.translation = Eigen::Vector3d(0.01, -0.02, 0.003);
  return m;
}

ContactPatch patch_of(const solver::Vertices& x) {
  ContactPatch patch;
  for (int v = 0; v < x.rows(); ++v) patch.add(v, x.row(v).transpose(), 1.0 + v);
  return patch;
}

TEST(ContactPatch, RecoversTheRigidMotionOfAPlanarPatch) {
  // Two parallel finger pads' contact lines, as rigid jaws touch a cylinder: a planar patch.
  solver::Vertices x(6, 3);
  x << 0, -0.02, 0.01, 0, 0, 0.01, 0, 0.02, 0.01, 0, -0.02, -0.01, 0, 0, -0.01, 0, 0.02, -0.01;
  const RigidMotion truth = some_motion();
  const RigidMotion fit = patch_of(x).motion(moved(x, truth));
  EXPECT_LT((fit.rotation - truth.rotation).norm(), 1e-12);
  EXPECT_LT((fit.translation - truth.translation).norm(), 1e-12);
  const Eigen::Vector3d far(0.05, 0.1, -0.2);  // a centre of mass away from the patch
  EXPECT_LT((fit(far) - truth(far)).norm(), 1e-12);
}

TEST(ContactPatch, APatchOnALineGivesItsMeansTranslationOnly) {
  // Points on one line do not say how far the patch turned about it.
  solver::Vertices x(3, 3);
  x << 0, 0, 0, 0, 0.01, 0, 0, 0.03, 0;
  RigidMotion shift;
  shift.translation = Eigen::Vector3d(0.001, 0.002, -0.004);
  const RigidMotion fit = patch_of(x).motion(moved(x, shift));
  EXPECT_TRUE(fit.rotation.isIdentity(0.0));
  EXPECT_LT((fit.translation - shift.translation).norm(), 1e-15);

  // Turned about the line itself the points stay, and so does the fit.
  RigidMotion turn;
  turn.rotation = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY()).matrix();
  const RigidMotion still = patch_of(x).motion(moved(x, turn));
  EXPECT_TRUE(still.rotation.isIdentity(0.0));
  EXPECT_LT(still.translation.norm(), 1e-15);
}

TEST(ContactPatch, WeighsVerticesByTheirForce) {
  // One vertex moves alone: the weighted mean moves by its share of the weights.
  solver::Vertices x(2, 3);
  x << 0, 0, 0, 0.01, 0, 0;
  ContactPatch patch;
  patch.add(0, x.row(0).transpose(), 3.0);
  patch.add(1, x.row(1).transpose(), 1.0);
  solver::Vertices y = x;
  y(1, 2) += 0.004;
  const RigidMotion fit = patch.motion(y);
  EXPECT_TRUE(fit.rotation.isIdentity(0.0));
  EXPECT_NEAR(fit.translation.z(), 0.001, 1e-15);
  EXPECT_TRUE(ContactPatch().motion(y).translation.isZero(0.0));  // an empty patch stays
}

}  // namespace
}  // namespace grip::trial
