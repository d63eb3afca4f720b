// Domain randomization: deterministic per seed, inside its ranges, log-uniform modulus.
#include "src/objects/domain_randomization.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace grip::objects {
namespace {

TEST(ObjectsDomainRandomizationTest, DeterministicAndWithinRanges) {
  const RandomizationRanges ranges;
  const ObjectMaterial a = randomize_material(ranges, 9);
  const ObjectMaterial b = randomize_material(ranges, 9);
  EXPECT_EQ(a.youngs_modulus, b.youngs_modulus);
  EXPECT_EQ(a.friction, b.friction);
  int below_geometric_mean = 0;
  const int draws = 2000;
  for (int seed = 0; seed < draws; ++seed) {
    const ObjectMaterial m = randomize_material(ranges, static_cast<std::uint64_t>(seed));
    ASSERT_GE(m.scale, ranges.scale_min);
    ASSERT_LE(m.scale, ranges.scale_max);
    ASSERT_GE(m.youngs_modulus, ranges.youngs_modulus_min);
    ASSERT_LE(m.youngs_modulus, ranges.youngs_modulus_max);
    ASSERT_GE(m.poisson_ratio, ranges.poisson_ratio_min);
    ASSERT_LT(m.poisson_ratio, 0.5);
    ASSERT_GE(m.density, ranges.density_min);
    ASSERT_LE(m.density, ranges.density_max);
    ASSERT_GE(m.friction, ranges.friction_min);
    ASSERT_LE(m.friction, ranges.friction_max);
    below_geometric_mean +=
        m.youngs_modulus < std::sqrt(ranges.youngs_modulus_min * ranges.youngs_modulus_max);
  }
  // Log-uniform: half the draws fall below the geometric mean (binomial sd ~ 22 of 2000;
  // the bound is 5 sd).
  EXPECT_NEAR(below_geometric_mean, draws / 2, 110);
}

TEST(ObjectsDomainRandomizationTest, ChangingOneRangeLeavesTheOtherPropertiesAlone) {
  RandomizationRanges ranges;
  const ObjectMaterial before = randomize_material(ranges, 3);
  ranges.friction_min = 0.9;
  const ObjectMaterial after = randomize_material(ranges, 3);
  EXPECT_EQ(before.youngs_modulus, after.youngs_modulus);
  EXPECT_EQ(before.scale, after.scale);
  EXPECT_NE(before.friction, after.friction);
}

TEST(ObjectsDomainRandomizationTest, InvalidRangesAreRefused) {
  RandomizationRanges ranges;
  ranges.poisson_ratio_max = 0.5;
  EXPECT_THROW(randomize_material(ranges, 1), std::invalid_argument);
  ranges = {};
  ranges.youngs_modulus_min = 0.0;
  EXPECT_THROW(randomize_material(ranges, 1), std::invalid_argument);
  ranges = {};
  ranges.scale_min = 2.0;  // above scale_max
  EXPECT_THROW(randomize_material(ranges, 1), std::invalid_argument);
}

}  // namespace
}  // namespace grip::objects
