// Tests of the entry points `grip synth` uses: the object spec and bimanual synthesis end to
// end (two rigid parallel-jaw grippers on a box), whose hands keep their clearance from the
// object and from each other, and the large categories that bimanual jobs grasp.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <string>

#include "src/geometry/mesh_io.hpp"
#include "src/geometry/primitives.hpp"
#include "src/synth/object_spec.hpp"
#include "src/synth/synthesize.hpp"
#include "tests/synth/exact_mesh_distance.hpp"

namespace grip::synth {
namespace {

TEST(SynthObjectSpecTest, CategoryNamesAndScaledMeshFiles) {
  const geometry::SurfaceMesh a = load_object("cylinder", 4), b = load_object("cylinder", 4);
  EXPECT_EQ(a.vertices, b.vertices);
  const auto file = std::filesystem::temp_directory_path() /
                    ("grip_synth_spec_" + std::to_string(::getpid()) + ".obj");
  geometry::write_obj(file, geometry::make_box(Eigen::Vector3d(2.0, 1.0, 1.0)));
  const geometry::SurfaceMesh scaled = load_object(file.string(), 0, 0.05);
  EXPECT_NEAR(scaled.vertices.col(0).maxCoeff() - scaled.vertices.col(0).minCoeff(), 0.1, 1e-12);
  EXPECT_THROW(load_object(file.string(), 0, -1.0), std::invalid_argument);
  std::filesystem::remove(file);
  try {
    load_object("teacup", 0);
    FAIL() << "no error for an unknown spec";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'teacup' is neither an object category (box,"),
              std::string::npos)
        << e.what();
  }
}

TEST(SynthSynthesizeTest, BimanualParallelJawsKeepClearOfObjectAndEachOther) {
  // A long bar: room for two grippers.
  const PreparedObject object(geometry::make_box(Eigen::Vector3d(0.3, 0.04, 0.04)));
  SynthesisParams params;
  params.antipodal.cloud_points = 2000;
  const SynthesisResult result = synthesize(
      object, grippers::gripper_type(grippers::GripperKind::kParallelJaw), true, params, 3, 6);
  ASSERT_GE(result.candidates.size(), 3u);
  ASSERT_LE(result.candidates.size(), 6u);
  const grippers::ParallelGripper gripper = grippers::make_rigid_jaw_gripper();
  const double target = params.antipodal.d_hat + params.antipodal.margin;
  for (const Candidate& c : result.candidates) {
    ASSERT_EQ(c.hands.size(), 2u);
    EXPECT_EQ(c.energies[0].name, "fc_bimanual");
    const geometry::SurfaceMesh right = posed_parallel_surface(gripper, c.hands[0]);
    const geometry::SurfaceMesh left = posed_parallel_surface(gripper, c.hands[1]);
    EXPECT_GE(testing::brute_force_distance(right, object.surface(), 0.01), target - 1e-12);
    EXPECT_GE(testing::brute_force_distance(left, object.surface(), 0.01), target - 1e-12);
    EXPECT_GE(testing::brute_force_distance(right, left, 0.01),
              params.bimanual.hand_clearance - 1e-12);
    EXPECT_EQ(testing::mesh_intersections(right, left), 0);
  }
}

// The library's large categories, bar and rod, are what bimanual jobs need: 20-60 cm long,
// 3-7 cm across, so that both a pair of fin-ray grippers (85 mm jaws) and a right and a left
// LEAP hand find candidates on them.
TEST(SynthSynthesizeTest, TheLargeCategoriesTakeBimanualFinRayAndHandCandidates) {
  for (const char* category : {"bar", "rod"}) {
    for (const std::uint64_t seed : {1, 2}) {
      const std::string name = std::string(category) + "/" + std::to_string(seed);
      const geometry::SurfaceMesh surface = load_object(category, seed);
      const Eigen::Vector3d extent =
          surface.vertices.colwise().maxCoeff() - surface.vertices.colwise().minCoeff();
      std::array<double, 3> sides = {extent.x(), extent.y(), extent.z()};
      std::sort(sides.begin(), sides.end());
      EXPECT_GE(sides[2], 0.2) << name;
      EXPECT_LE(sides[1], 0.07 + 1e-9) << name;
      const PreparedObject object(surface);
      const SynthesisParams params;  // the hand needs its default annealing steps on a rod
      EXPECT_GE(synthesize(object, grippers::gripper_type(grippers::GripperKind::kFinRay), true,
                           params, 1, 2)
                    .candidates.size(),
                1u)
          << name;
      EXPECT_GE(synthesize(object, grippers::gripper_type(grippers::GripperKind::kLeap), true,
                           params, 1, 1)
                    .candidates.size(),
                1u)
          << name;
    }
  }
}

}  // namespace
}  // namespace grip::synth
