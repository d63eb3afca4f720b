// Tests of the hand optimizer and its clearance fix: every emitted hand keeps d_hat + margin
// from the object (independent exact check), no two non-adjacent links intersect, and the
// candidates do not depend on the thread count.
#include <gtest/gtest.h>

#include <limits>

#include <tbb/global_control.h>

#include "src/synth/hand_clearance_fix.hpp"
#include "src/synth/hand_optimizer.hpp"
#include "tests/synth/exact_mesh_distance.hpp"
#include "tests/synth/hand_fixture.hpp"

namespace grip::synth {
namespace {

HandOptimizerParams small_params() {
  HandOptimizerParams params;
  params.steps = 60;
  params.penetration_points = 300;
  params.block = 4;
  params.max_force_closure_error = std::numeric_limits<double>::infinity();  // tested below
  return params;
}

void expect_clear_and_self_free(const HandGrasp& grasp, double target) {
  const PreparedHand& hand = testing::right_hand();
  const PreparedObject& object = testing::sphere_object();
  const auto poses = hand.kinematics().link_poses(grasp.pose, grasp.joints);
  const geometry::SurfaceMesh surface = hand.kinematics().posed_surface(poses);
  EXPECT_GE(testing::brute_force_distance(surface, object.surface(), 0.01), target - 1e-12);
  EXPECT_EQ(testing::mesh_intersections(surface, object.surface()), 0);
  for (int l = 0; l < hand.link_count(); ++l) {  // no link inside the object
    const geometry::SurfaceMesh link = hand.posed_link(poses, l);
    if (link.vertices.rows() > 0) {
      EXPECT_LT(object.signed_distance()(link.vertices.row(0).transpose()), 0.0);
    }
  }
  for (int a = 0; a < hand.link_count(); ++a) {
    for (int b = a + 1; b < hand.link_count(); ++b) {
      if (hand.adjacent(a, b)) continue;
      EXPECT_EQ(testing::mesh_intersections(hand.posed_link(poses, a), hand.posed_link(poses, b)),
                0)
          << "links " << a << " and " << b;
    }
  }
}

TEST(SynthHandOptimizerTest, CandidatesAreClearSelfFreeAndThreadIndependent) {
  const HandOptimizerParams params = small_params();
  const auto run = [&](int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return optimize_hand_grasps(testing::sphere_object(), testing::right_hand(), params, 5, 3);
  };
  const SynthesisResult one = run(1), two = run(2);
  ASSERT_EQ(one.candidates.size(), 3u);
  ASSERT_EQ(two.candidates.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const Candidate& c = one.candidates[i];
    EXPECT_EQ(c.hands[0].pose.matrix(), two.candidates[i].hands[0].pose.matrix());
    EXPECT_EQ(c.hands[0].joints, two.candidates[i].hands[0].joints);
    EXPECT_EQ(c.energies, two.candidates[i].energies);
    EXPECT_TRUE(testing::right_hand().kinematics().within_limits(c.hands[0].joints));
    EXPECT_EQ(c.hands[0].contacts.rows(), params.contacts);
    EXPECT_GE(c.min_distance, params.clearance.d_hat + params.clearance.margin);
    expect_clear_and_self_free(c.hands[0], params.clearance.d_hat + params.clearance.margin);
  }
}

// The energies written are those of the grasp returned (after the clearance fix), and none of
// its grasps is further from force closure than the gate allows.
TEST(SynthHandOptimizerTest, CandidatesPassTheForceClosureGateOnTheirOwnContacts) {
  HandOptimizerParams params = small_params();
  params.steps = 300;
  params.max_force_closure_error = 0.5;
  const PreparedObject& object = testing::sphere_object();
  const SynthesisResult result = optimize_hand_grasps(object, testing::right_hand(), params, 7, 2);
  ASSERT_EQ(result.candidates.size(), 2u);
  EXPECT_GT(result.rejections.at("not a force closure"), 0);
  for (const Candidate& c : result.candidates) {
    const HandGrasp& grasp = c.hands[0];
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> points = grasp.contacts;
    points.rowwise() -= object.centroid().transpose();
    const double fc = force_closure_error(points, grasp.contact_normals);
    ASSERT_EQ(c.energies[0].name, "fc");
    EXPECT_NEAR(c.energies[0].value, fc, 1e-12);
    EXPECT_LE(fc, params.max_force_closure_error);
  }
}

TEST(SynthHandClearanceFixTest, PushesAPenetratingPalmAndFingersOut) {
  const PreparedHand& hand = testing::right_hand();
  const PreparedObject& object = testing::sphere_object();
  HandState state;
  state.base = testing::palm_over_sphere(0.037);  // palm 3 mm deep
  state.joints = Eigen::VectorXd::Constant(16, 0.6);
  const double before = object.clearance(
      hand.kinematics().posed_surface(hand.kinematics().link_poses(state.base, state.joints)),
      0.01);
  ASSERT_EQ(before, 0.0);
  const ClearanceFixParams params;
  const std::optional<FixedHand> fixed = fix_hand_clearance(hand, object, state, params);
  ASSERT_TRUE(fixed.has_value());
  HandGrasp grasp;
  grasp.pose = fixed->state.base;
  grasp.joints = fixed->state.joints;
  expect_clear_and_self_free(grasp, params.d_hat + params.margin);
}

}  // namespace
}  // namespace grip::synth
