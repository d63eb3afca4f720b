#include "src/grippers/parallel_gripper.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "src/geometry/mesh_measures.hpp"
#include "src/geometry/tet_quality.hpp"
#include "tests/grippers/mesh_checks.hpp"

namespace grip::grippers {
namespace {

geometry::Vertices finger_vertices(const ParallelGripper& gripper, Jaw jaw, double opening) {
  const Eigen::Isometry3d pose = gripper.finger_pose(jaw, opening);
  geometry::Vertices v = gripper.finger_surface.vertices;
  for (Eigen::Index i = 0; i < v.rows(); ++i) v.row(i) = (pose * v.row(i).transpose()).transpose();
  return v;
}

TEST(GrippersParallelJaw, ContactFacesSitAtHalfTheOpeningOnTheClosingAxis) {
  const ParallelGripper gripper = make_rigid_jaw_gripper();
  for (const double opening : {0.0, 0.03, 0.085}) {
    const geometry::Vertices positive = finger_vertices(gripper, Jaw::kPositive, opening);
    const geometry::Vertices negative = finger_vertices(gripper, Jaw::kNegative, opening);
    EXPECT_NEAR(positive.col(1).minCoeff(), 0.5 * opening, 1e-15);
    EXPECT_NEAR(negative.col(1).maxCoeff(), -0.5 * opening, 1e-15);
    // Both fingers extend from the mount plane along the approach axis.
    EXPECT_NEAR(positive.col(2).minCoeff(), 0.0, 1e-15);
    EXPECT_NEAR(negative.col(2).maxCoeff(), 0.05, 1e-15);
  }
}

TEST(GrippersParallelJaw, NegativeFingerIsThePositiveTurnedHalfwayAboutZ) {
  const ParallelGripper gripper = make_umi_soft_gripper();
  const double opening = 0.04;
  const geometry::Vertices positive = finger_vertices(gripper, Jaw::kPositive, opening);
  const geometry::Vertices negative = finger_vertices(gripper, Jaw::kNegative, opening);
  ASSERT_EQ(positive.rows(), negative.rows());
  for (Eigen::Index i = 0; i < positive.rows(); ++i) {
    EXPECT_NEAR(negative(i, 0), -positive(i, 0), 1e-15);
    EXPECT_NEAR(negative(i, 1), -positive(i, 1), 1e-15);
    EXPECT_EQ(negative(i, 2), positive(i, 2));
  }
}

TEST(GrippersParallelJaw, OpeningIsLimitedTo0To85Millimetres) {
  for (const ParallelGripper& gripper : {make_rigid_jaw_gripper(), make_umi_soft_gripper()}) {
    EXPECT_EQ(gripper.min_opening, 0.0);
    EXPECT_EQ(gripper.max_opening, 0.085);
    EXPECT_NO_THROW(gripper.finger_pose(Jaw::kPositive, 0.0));
    EXPECT_NO_THROW(gripper.finger_pose(Jaw::kNegative, 0.085));
    EXPECT_THROW(gripper.finger_pose(Jaw::kPositive, -1e-6), std::out_of_range);
    EXPECT_THROW(gripper.finger_pose(Jaw::kNegative, 0.0851), std::out_of_range);
  }
}

TEST(GrippersParallelJaw, RigidFingersAreClosedBoxesOfTheGivenSize) {
  const RigidJawOptions o;
  const ParallelGripper gripper = make_rigid_jaw_gripper(o);
  EXPECT_FALSE(gripper.soft_finger.has_value());
  const geometry::SurfaceMesh both = gripper.surface(0.06);
  EXPECT_TRUE(testing::is_closed_and_oriented(both));
  EXPECT_NEAR(geometry::surface_volume(both), 2.0 * o.width * o.thickness * o.length, 1e-18);
}

TEST(GrippersParallelJaw, SoftFingerSurfaceEnclosesItsTetMesh) {
  const ParallelGripper gripper = make_umi_soft_gripper();
  ASSERT_TRUE(gripper.soft_finger.has_value());
  EXPECT_TRUE(testing::is_closed_and_oriented(gripper.finger_surface));
  const double tet_volume = geometry::tet_quality(gripper.soft_finger->mesh).total_volume;
  EXPECT_NEAR(geometry::surface_volume(gripper.surface(0.085)), 2.0 * tet_volume, 1e-12);
}

}  // namespace
}  // namespace grip::grippers
