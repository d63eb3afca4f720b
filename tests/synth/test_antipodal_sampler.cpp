// Tests of the antipodal sampler: every emitted candidate keeps d_hat + margin from the object
// (independent exact check), its contacts are antipodal within the friction cone, its opening
// fits the gripper, and the candidates do not depend on the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/global_control.h>

#include "src/geometry/primitives.hpp"
#include "src/objects/object_library.hpp"
#include "src/synth/antipodal_sampler.hpp"
#include "tests/synth/exact_mesh_distance.hpp"

namespace grip::synth {
namespace {

AntipodalParams small_params() {
  AntipodalParams params;
  params.cloud_points = 1500;
  params.block = 32;
  return params;
}

void expect_valid(const PreparedObject& object, const grippers::ParallelGripper& gripper,
                  const AntipodalParams& params, const std::vector<Candidate>& candidates) {
  const double target = params.d_hat + params.margin;
  const double cos_cone = std::cos(std::atan(params.friction));
  for (const Candidate& c : candidates) {
    ASSERT_EQ(c.hands.size(), 1u);
    const HandGrasp& hand = c.hands[0];
    EXPECT_TRUE((hand.pose.linear().transpose() * hand.pose.linear()).isIdentity(1e-12));
    EXPECT_NEAR(hand.pose.linear().determinant(), 1.0, 1e-12);
    ASSERT_EQ(hand.joints.size(), 1);
    EXPECT_GE(hand.joints(0), gripper.min_opening);
    EXPECT_LE(hand.joints(0), gripper.max_opening);
    const geometry::SurfaceMesh posed = posed_parallel_surface(gripper, hand);
    const double distance = testing::brute_force_distance(posed, object.surface(), 0.02);
    EXPECT_GT(distance, params.d_hat);
    EXPECT_GE(distance, target - 1e-12);
    EXPECT_NEAR(distance, c.min_distance, 1e-12);
    EXPECT_EQ(testing::mesh_intersections(posed, object.surface()), 0);
    EXPECT_LT(object.signed_distance()(posed.vertices.row(0).transpose()), 0.0);  // not inside
    // Contact 0 faces the -y jaw, contact 1 the +y jaw, both within the friction cone.
    const Eigen::Vector3d closing = hand.pose.linear().col(1);
    EXPECT_GE(-hand.contact_normals.row(0).dot(closing), cos_cone - 1e-12);
    EXPECT_GE(hand.contact_normals.row(1).dot(closing), cos_cone - 1e-12);
    EXPECT_LE(c.energies[0].value, std::atan(params.friction) + 1e-12);
  }
}

TEST(SynthAntipodalSamplerTest, RigidJawCandidatesOnACylinderAreClearAndAntipodal) {
  const PreparedObject object(
      objects::generate_surface(objects::sample_shape(objects::ObjectCategory::kCylinder, 3)));
  const grippers::ParallelGripper gripper = grippers::make_rigid_jaw_gripper();
  const AntipodalParams params = small_params();
  const SynthesisResult result =
      sample_antipodal_grasps(object, gripper, grippers::GripperKind::kParallelJaw, params, 42, 8);
  ASSERT_EQ(result.candidates.size(), 8u);
  EXPECT_GE(result.attempts, result.accepted);
  expect_valid(object, gripper, params, result.candidates);
}

TEST(SynthAntipodalSamplerTest, FinRayCandidatesOnAMugAreClearAndAntipodal) {
  // Mug seed 6: the production finger, 41.5 mm deep at its mount, clears few mugs' walls and
  // handles (seeds 1-5 give 0-4 of 5 candidates in 1,000 attempts).
  const PreparedObject object(
      objects::generate_surface(objects::sample_shape(objects::ObjectCategory::kMug, 6)));
  const grippers::ParallelGripper gripper = grippers::make_umi_soft_gripper();
  const AntipodalParams params = small_params();
  const SynthesisResult result =
      sample_antipodal_grasps(object, gripper, grippers::GripperKind::kFinRay, params, 7, 5);
  ASSERT_EQ(result.candidates.size(), 5u);
  expect_valid(object, gripper, params, result.candidates);
}

TEST(SynthAntipodalSamplerTest, FinRayGraspsReachTheDepthWhereTheFingersSqueeze50N) {
  // The fin-ray builds the grip force within its stroke only on objects that reach near enough
  // its mount: 0.45 of its length for the solid production finger, 0.75 for the hollow 80 mm
  // one; rigid jaws take any depth. Cylinder seed 1 has rim grasps 2 cm deep.
  const grippers::ParallelGripper fin_ray = grippers::make_umi_soft_gripper();
  EXPECT_DOUBLE_EQ(fin_ray.min_grasp_depth, 0.45 * grippers::FinRayOptions{}.length);
  EXPECT_DOUBLE_EQ(
      grippers::make_umi_soft_gripper(grippers::fin_ray_80mm_options()).min_grasp_depth,
      0.75 * 0.080);
  EXPECT_EQ(grippers::make_rigid_jaw_gripper().min_grasp_depth, 0.0);
  const PreparedObject object(
      objects::generate_surface(objects::sample_shape(objects::ObjectCategory::kCylinder, 1)));
  const AntipodalParams params;
  const auto depths = [&](const grippers::ParallelGripper& gripper, SynthesisResult* out) {
    *out = sample_antipodal_grasps(object, gripper, grippers::GripperKind::kFinRay, params, 1, 8);
    std::vector<double> d;
    for (const Candidate& c : out->candidates) d.push_back(c.energies[1].value);
    return d;
  };
  SynthesisResult gated, ungated;
  const std::vector<double> deep = depths(fin_ray, &gated);
  ASSERT_EQ(deep.size(), 8u);
  for (double d : deep) EXPECT_GE(d, fin_ray.min_grasp_depth);
  EXPECT_GT(gated.rejections["too shallow for the fingers to reach the grip force"], 0);
  grippers::ParallelGripper any_depth = fin_ray;
  any_depth.min_grasp_depth = 0.0;
  const std::vector<double> all = depths(any_depth, &ungated);
  EXPECT_LT(*std::min_element(all.begin(), all.end()), fin_ray.min_grasp_depth);
  expect_valid(object, fin_ray, params, gated.candidates);
}

TEST(SynthAntipodalSamplerTest, SameSeedSameCandidatesWhateverTheThreads) {
  const PreparedObject object(
      objects::generate_surface(objects::sample_shape(objects::ObjectCategory::kCylinder, 3)));
  const grippers::ParallelGripper gripper = grippers::make_rigid_jaw_gripper();
  const AntipodalParams params = small_params();
  const auto run = [&](int threads, std::uint64_t seed) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return sample_antipodal_grasps(object, gripper, grippers::GripperKind::kParallelJaw, params,
                                   seed, 6);
  };
  const SynthesisResult one = run(1, 9), two = run(2, 9), other = run(2, 10);
  ASSERT_EQ(one.candidates.size(), 6u);
  ASSERT_EQ(two.candidates.size(), 6u);
  ASSERT_FALSE(other.candidates.empty());
  EXPECT_EQ(one.attempts, two.attempts);
  for (std::size_t i = 0; i < one.candidates.size(); ++i) {
    EXPECT_EQ(one.candidates[i].hands[0].pose.matrix(), two.candidates[i].hands[0].pose.matrix());
    EXPECT_EQ(one.candidates[i].hands[0].joints, two.candidates[i].hands[0].joints);
    EXPECT_EQ(one.candidates[i].energies, two.candidates[i].energies);
  }
  EXPECT_NE(one.candidates[0].hands[0].pose.matrix(), other.candidates[0].hands[0].pose.matrix());
}

TEST(SynthAntipodalSamplerTest, ObjectWiderThanTheOpeningGivesNothing) {
  // A 0.2 m sphere: no two antipodal points fit within the 85 mm opening.
  const PreparedObject object(geometry::make_sphere(0.1, 48, 24));
  AntipodalParams params = small_params();
  params.max_attempts_per_candidate = 256;
  const SynthesisResult result =
      sample_antipodal_grasps(object, grippers::make_rigid_jaw_gripper(),
                              grippers::GripperKind::kParallelJaw, params, 1, 1);
  EXPECT_TRUE(result.candidates.empty());
  EXPECT_EQ(result.attempts, 256);
  EXPECT_EQ(result.accepted, 0);
}

}  // namespace
}  // namespace grip::synth
