// The hard-case suite of `grip bench hard`: every case keeps every invariant after every step,
// and the checks really catch what they look for (so the suite cannot pass vacuously).
#include <gtest/gtest.h>

#include <cmath>

#include "bench/hard/hard_benchmark.hpp"
#include "bench/hard/hard_suite.hpp"
#include "src/geometry/primitives.hpp"

namespace {

using grip::bench::HardCase;
using grip::bench::HardCaseResult;

grip::solver::BodyDescription affine_cube(const std::string& name, double x) {
  grip::solver::BodyDescription body;
  body.name = name;
  body.type = grip::solver::BodyType::kAffine;
  const grip::geometry::SurfaceMesh box = grip::geometry::make_box({0.02, 0.02, 0.02});
  body.vertices = box.vertices;
  body.triangles = box.triangles;
  body.pose.position = {x, 0, 0};
  return body;
}

// Two cubes 2 cm wide whose centres are `distance` apart along x, no gravity.
HardCase two_cubes(double distance) {
  HardCase c;
  c.name = "two_cubes";
  c.scene.sim.gravity.setZero();
  c.scene.bodies = {affine_cube("a", 0.0), affine_cube("b", distance)};
  c.steps = 2;
  return c;
}

TEST(HardCases, EveryCaseKeepsEveryInvariantAfterEveryStep) {
  const std::vector<HardCase> cases = grip::bench::hard_cases();
  ASSERT_GE(cases.size(), 12u);
  const std::vector<HardCaseResult> results = grip::bench::run_hard_cases(cases, 2);
  for (const HardCaseResult& r : results) {
    SCOPED_TRACE(r.name);
    EXPECT_TRUE(r.intersection_free()) << r.intersecting_steps << " step(s) intersecting";
    EXPECT_TRUE(r.inversion_free()) << r.inverted_steps << " step(s) inverted";
    EXPECT_TRUE(r.outcome_as_expected()) << grip::bench::solver_outcome(r);
    EXPECT_EQ(r.physical_failure, "");
    EXPECT_TRUE(r.passed());
    if (r.failure_expected) {
      // It must have been refused on the way, after taking some steps.
      EXPECT_GT(r.steps.size(), 0u);
      EXPECT_LT(static_cast<int>(r.steps.size()), r.planned_steps);
    } else {
      EXPECT_EQ(static_cast<int>(r.steps.size()), r.planned_steps);
      // Contact really happened: something came within d_hat, and stayed apart.
      EXPECT_TRUE(std::isfinite(r.min_distance_over_d_hat()));
      EXPECT_GT(r.min_distance_over_d_hat(), 0.0);
    }
    EXPECT_GT(r.min_volume_ratio(), 0.0);
  }
  EXPECT_TRUE(grip::bench::all_passed(results));
}

TEST(HardCases, InvariantCheckCountsIntersectionsOfABadState) {
  // The solver never accepts an intersecting state, so the checker is tested on one it is given.
  const auto overlapping = grip::solver::Model::build(two_cubes(0.015).scene);
  const grip::solver::Environment bad(overlapping);
  EXPECT_GT(grip::bench::check_invariants(bad).intersections, 0);
  EXPECT_FALSE(grip::bench::check_invariants(bad).holds());

  const auto apart = grip::solver::Model::build(two_cubes(0.025).scene);
  const grip::solver::Environment good(apart);
  EXPECT_EQ(grip::bench::check_invariants(good).intersections, 0);
  EXPECT_TRUE(grip::bench::check_invariants(good).holds());
}

TEST(HardCases, ACaseFailsWhenTheSolverFailsUnexpectedly) {
  const HardCaseResult r = grip::bench::run_hard_case(two_cubes(0.015));
  EXPECT_NE(r.solver_failure.find("intersecting start"), std::string::npos) << r.solver_failure;
  EXPECT_FALSE(r.outcome_as_expected());
  EXPECT_FALSE(r.passed());
}

TEST(HardCases, ACaseFailsWhenAnExpectedFailureDoesNotHappen) {
  HardCase c = two_cubes(0.025);
  c.failure_expected = true;
  const HardCaseResult r = grip::bench::run_hard_case(c);
  EXPECT_EQ(r.solver_failure, "");
  EXPECT_FALSE(r.passed());
}

TEST(HardCases, ACaseFailsWhenItsPhysicalCheckBreaks) {
  HardCase c = two_cubes(0.025);
  c.check = [](const grip::solver::Environment&, bool last) {
    return last ? std::string("broken on purpose") : std::string();
  };
  const HardCaseResult r = grip::bench::run_hard_case(c);
  EXPECT_EQ(r.physical_failure, "step 2: broken on purpose");
  EXPECT_FALSE(r.passed());
  c.check = {};
  EXPECT_TRUE(grip::bench::run_hard_case(c).passed());
}

TEST(HardCases, ResultsDoNotDependOnTheThreadCount) {
  const std::vector<HardCase> cases =
      grip::bench::select_hard_cases({"plate_drop_flat", "mass_ratio_1e3", "start_within_d_hat"});
  const std::vector<HardCaseResult> one = grip::bench::run_hard_cases(cases, 1);
  const std::vector<HardCaseResult> two = grip::bench::run_hard_cases(cases, 2);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    SCOPED_TRACE(one[i].name);
    ASSERT_EQ(one[i].steps.size(), two[i].steps.size());
    for (std::size_t s = 0; s < one[i].steps.size(); ++s) {
      EXPECT_EQ(one[i].steps[s].newton_iterations, two[i].steps[s].newton_iterations);
      EXPECT_EQ(one[i].steps[s].min_distance, two[i].steps[s].min_distance);
      EXPECT_EQ(one[i].steps[s].min_volume_ratio, two[i].steps[s].min_volume_ratio);
    }
  }
}

TEST(HardCases, UnknownCaseNamesAreRefused) {
  EXPECT_THROW(grip::bench::select_hard_cases({"no_such_case"}), std::invalid_argument);
}

}  // namespace
