// Finite-difference checks of every term of the hand energy's gradient (central differences
// over base translation, base rotation and joints), and exact values of E_fc and E_joints.
#include <gtest/gtest.h>

#include <cmath>

#include "src/geometry/surface_sampling.hpp"
#include "src/synth/hand_energy.hpp"
#include "tests/synth/hand_fixture.hpp"

namespace grip::synth {
namespace {

enum class Term { kFc, kDis, kPen, kSpen, kNormal };

HandEnergyWeights only(Term term) {
  HandEnergyWeights w{0, 0, 0, 0, 0, 0};
  switch (term) {
    case Term::kFc:
      w.fc = 1;
      break;
    case Term::kDis:
      w.dis = 1;
      break;
    case Term::kPen:
      w.pen = 1;
      break;
    case Term::kSpen:
      w.spen = 1;
      break;
    case Term::kNormal:
      w.normal = 1;
      break;
  }
  return w;
}

// A state with every term active on the sphere: the palm 2 mm into it, index and middle
// fingers spread into each other, the fingers half curled.
HandState active_state() {
  const PreparedHand& hand = testing::right_hand();
  HandState state;
  state.base = testing::palm_over_sphere(0.038);
  state.joints = Eigen::VectorXd::Constant(16, 0.4);
  state.joints(hand.kinematics().dof_index("index_abd")) = -0.6;
  state.joints(hand.kinematics().dof_index("middle_abd")) = 0.6;
  state.contacts = {3, 18, 33, 50};
  return state;
}

// E_fc and E_normal use the normal of the object's closest triangle, constant almost everywhere
// but jumping where the closest triangle changes; they are checked on the slab, whose top face
// is closest to every contact. The other terms are checked on the sphere.
void check_gradient(Term term, const char* name, const PreparedObject& object) {
  const PreparedHand& hand = testing::right_hand();
  const geometry::SurfaceSamples points = geometry::sample_surface(object.surface(), 400, 3);
  const HandEnergy energy(hand, object, points.points, only(term));
  const HandState state = active_state();
  Eigen::VectorXd gradient;
  const double value = energy.evaluate(state, &gradient).total;
  ASSERT_GT(value, 0.0) << name << " is not active in the test state";
  const double h = 1e-7;
  for (int i = 0; i < gradient.size(); ++i) {
    Eigen::VectorXd step = Eigen::VectorXd::Zero(gradient.size());
    step(i) = h;
    const double plus = energy.evaluate(HandEnergy::moved(state, step), nullptr).total;
    const double minus = energy.evaluate(HandEnergy::moved(state, -step), nullptr).total;
    const double fd = (plus - minus) / (2 * h);
    EXPECT_NEAR(gradient(i), fd, 1e-5 * std::max(1.0, std::abs(fd)))
        << name << ", coordinate " << i;
  }
}

TEST(SynthHandEnergyTest, ForceClosureGradientMatchesFiniteDifferences) {
  check_gradient(Term::kFc, "E_fc", testing::slab_object());
}
TEST(SynthHandEnergyTest, DistanceGradientMatchesFiniteDifferences) {
  check_gradient(Term::kDis, "E_dis", testing::sphere_object());
}
TEST(SynthHandEnergyTest, PenetrationGradientMatchesFiniteDifferences) {
  check_gradient(Term::kPen, "E_pen", testing::sphere_object());
}
TEST(SynthHandEnergyTest, SelfPenetrationGradientMatchesFiniteDifferences) {
  check_gradient(Term::kSpen, "E_spen", testing::sphere_object());
}
TEST(SynthHandEnergyTest, NormalAlignmentGradientMatchesFiniteDifferences) {
  check_gradient(Term::kNormal, "E_normal", testing::slab_object());
}

TEST(SynthHandEnergyTest, JointLimitEnergyAndGradient) {
  const Eigen::Vector3d lower(-1, 0, 0), upper(1, 2, 0.5);
  Eigen::VectorXd gradient;
  EXPECT_EQ(joint_limit_energy(Eigen::Vector3d(0.5, 1, 0.2), lower, upper, &gradient), 0.0);
  EXPECT_TRUE(gradient.isZero());
  const Eigen::Vector3d q(-1.25, 2.5, 0.25);
  EXPECT_DOUBLE_EQ(joint_limit_energy(q, lower, upper, &gradient), 0.75);
  const double h = 1e-6;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(i);
    const double fd = (joint_limit_energy(q + step, lower, upper, nullptr) -
                       joint_limit_energy(q - step, lower, upper, nullptr)) /
                      (2 * h);
    EXPECT_NEAR(gradient(i), fd, 1e-8);
  }
}

TEST(SynthHandEnergyTest, ForceClosureErrorOfBalancedAndUnbalancedContacts) {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> points(2, 3), normals(2, 3);
  points << 0.05, 0, 0, -0.05, 0, 0;
  normals << 1, 0, 0, -1, 0, 0;  // opposite contacts on a line through the reference point
  EXPECT_NEAR(force_closure_error(points, normals), 0.0, 1e-15);
  normals.row(1) << 0, 1, 0;  // net force (1, 1, 0), torque -0.05 z
  EXPECT_NEAR(force_closure_error(points, normals), std::sqrt(2.0 + 0.0025), 1e-15);
}

TEST(SynthHandEnergyTest, TotalIsTheWeightedSumOfTerms) {
  const geometry::SurfaceSamples points =
      geometry::sample_surface(testing::sphere_object().surface(), 400, 3);
  const HandEnergy energy(testing::right_hand(), testing::sphere_object(), points.points);
  const HandEnergyTerms t = energy.evaluate(active_state(), nullptr);
  EXPECT_GT(t.pen, 0.0);
  EXPECT_GT(t.spen, 0.0);
  EXPECT_NEAR(t.total, t.fc + 100 * t.dis + 100 * t.pen + 10 * t.spen + t.joints + t.normal, 1e-12);
}

}  // namespace
}  // namespace grip::synth
