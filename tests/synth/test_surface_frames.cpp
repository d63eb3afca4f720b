// Tests of the GPD-style local frames on a cylinder, whose curvature axis is its own axis.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "src/geometry/primitives.hpp"
#include "src/geometry/surface_sampling.hpp"
#include "src/synth/surface_frames.hpp"

namespace grip::synth {
namespace {

TEST(SynthSurfaceFramesTest, CylinderSideFramesFollowTheAxis) {
  const geometry::SurfaceSamples cloud =
      geometry::sample_surface(geometry::make_cylinder(0.03, 0.12, 96), 4000, 7);
  const SurfaceFrames frames(cloud, 0.01);
  int checked = 0;
  for (int i = 0; i < cloud.points.rows(); ++i) {
    const Eigen::Vector3d p = cloud.points.row(i).transpose();
    if (std::abs(p.z()) > 0.04) continue;  // away from the rims
    const SurfaceFrame f = frames.at(i);
    const Eigen::Vector3d radial = Eigen::Vector3d(p.x(), p.y(), 0.0).normalized();
    EXPECT_GT(f.normal.dot(radial), 0.995) << i;
    EXPECT_GT(std::abs(f.curvature_axis.z()), 0.995) << i;
    EXPECT_TRUE(f.normal.cross(f.binormal).isApprox(f.curvature_axis, 1e-12));
    EXPECT_NEAR(f.binormal.norm(), 1.0, 1e-12);
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

TEST(SynthSurfaceFramesTest, NeighboursAreExactlyThoseWithinTheRadius) {
  const geometry::SurfaceSamples cloud =
      geometry::sample_surface(geometry::make_box(Eigen::Vector3d(0.1, 0.05, 0.02)), 2000, 3);
  const double radius = 0.012;
  const SurfaceFrames frames(cloud, radius);
  const Eigen::Vector3d query = cloud.points.row(17).transpose();
  std::vector<int> found = frames.neighbours(query);
  std::sort(found.begin(), found.end());
  std::vector<int> expected;
  for (int i = 0; i < cloud.points.rows(); ++i) {
    if ((cloud.points.row(i).transpose() - query).norm() <= radius) expected.push_back(i);
  }
  EXPECT_EQ(found, expected);
}

}  // namespace
}  // namespace grip::synth
