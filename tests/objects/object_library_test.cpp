// Every procedural category yields a closed, manifold, outward, self-intersection-free
// surface; sampling is deterministic and in range; closed-form volumes where they exist.
#include "src/objects/object_library.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "src/geometry/mesh_measures.hpp"
#include "src/geometry/repair.hpp"

namespace grip::objects {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(ObjectsObjectLibraryTest, EveryCategoryIsAValidClosedSolid) {
  EXPECT_GE(all_object_categories().size(), 12u);
  for (const ObjectCategory category : all_object_categories()) {
    for (std::uint64_t seed : {1u, 2u}) {
      const ObjectShape shape = sample_shape(category, seed);
      const geometry::SurfaceMesh surface = generate_surface(shape, 32);
      // Repair with wrapping disabled fails on anything open, non-manifold or
      // self-intersecting; a valid solid passes with nothing to change.
      geometry::RepairOptions strict;
      strict.allow_alpha_wrap = false;
      strict.fill_holes = false;
      const geometry::RepairedSurface repaired =
          geometry::repair_surface(surface, strict, std::string(category_name(category)));
      EXPECT_EQ(repaired.report.faces_reoriented, 0) << category_name(category);
      EXPECT_EQ(repaired.report.edges_stitched, 0) << category_name(category);
      EXPECT_FALSE(repaired.report.self_intersecting) << category_name(category);
      EXPECT_GT(geometry::surface_volume(surface), 0.0) << category_name(category);
      EXPECT_GT(thinnest_feature(shape), 0.0);
    }
  }
}

TEST(ObjectsObjectLibraryTest, SamplingIsDeterministicAndWithinRanges) {
  for (const ObjectCategory category : all_object_categories()) {
    const ObjectShape a = sample_shape(category, 42);
    const ObjectShape b = sample_shape(category, 42);
    const ObjectShape c = sample_shape(category, 43);
    EXPECT_EQ(a.parameters, b.parameters);
    EXPECT_NE(a.parameters, c.parameters);
    const auto ranges = parameter_ranges(category);
    ASSERT_EQ(a.parameters.size(), ranges.size());
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      EXPECT_GE(a.parameters[i], ranges[i].min);
      EXPECT_LE(a.parameters[i], ranges[i].max);
    }
  }
}

TEST(ObjectsObjectLibraryTest, ClosedFormVolumes) {
  const geometry::SurfaceMesh box = generate_surface({ObjectCategory::kBox, {0.1, 0.05, 0.04}});
  EXPECT_NEAR(geometry::surface_volume(box), 0.1 * 0.05 * 0.04, 1e-15);
  const int n = 64;
  const geometry::SurfaceMesh cylinder =
      generate_surface({ObjectCategory::kCylinder, {0.03, 0.1}}, n);
  EXPECT_NEAR(geometry::surface_volume(cylinder),
              0.5 * n * 0.03 * 0.03 * std::sin(2 * kPi / n) * 0.1, 1e-15);
  // A tessellated sphere is inscribed: slightly smaller than 4/3 pi r^3, by O(1/n^2).
  const geometry::SurfaceMesh sphere = generate_surface({ObjectCategory::kSphere, {0.05}}, n);
  const double ball = 4.0 / 3.0 * kPi * std::pow(0.05, 3);
  EXPECT_LT(geometry::surface_volume(sphere), ball);
  EXPECT_GT(geometry::surface_volume(sphere), ball * (1.0 - 2.0 * std::pow(2 * kPi / n, 2)));
  // A mug is its cup plus a handle: more volume than the cup.
  const geometry::SurfaceMesh cup =
      generate_surface({ObjectCategory::kCup, {0.04, 0.1, 0.005, 0.008}}, n);
  const geometry::SurfaceMesh mug =
      generate_surface({ObjectCategory::kMug, {0.04, 0.1, 0.005, 0.008, 0.025, 0.006}}, n);
  EXPECT_GT(geometry::surface_volume(mug), geometry::surface_volume(cup));
}

TEST(ObjectsObjectLibraryTest, NamesRoundTripAndBadInputIsRefused) {
  for (const ObjectCategory category : all_object_categories()) {
    EXPECT_EQ(parse_object_category(category_name(category)), category);
  }
  try {
    parse_object_category("teacup");
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("mug"), std::string::npos) << "lists the known names";
  }
  EXPECT_THROW(generate_surface({ObjectCategory::kSphere, {0.5}}), std::invalid_argument);
  EXPECT_THROW(generate_surface({ObjectCategory::kSphere, {0.05, 0.05}}), std::invalid_argument);
}

}  // namespace
}  // namespace grip::objects
