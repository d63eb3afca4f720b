// Tests of k-means on well-separated blobs.
#include <gtest/gtest.h>

#include <set>

#include "src/synth/candidate_random.hpp"
#include "src/synth/kmeans.hpp"

namespace grip::synth {
namespace {

TEST(SynthKmeansTest, RecoversSeparatedBlobsAndTheirMeans) {
  const Eigen::Vector3d centres[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}};
  Points3 points(90, 3);
  CandidateRandom random(5, 0, 0);
  for (int i = 0; i < 90; ++i) {
    points.row(i) =
        (centres[i % 3] + 0.01 * Eigen::Vector3d(random.normal(), random.normal(), random.normal()))
            .transpose();
  }
  const Clustering c = kmeans(points, 3, 11);
  ASSERT_EQ(c.centres.rows(), 3);
  for (int blob = 0; blob < 3; ++blob) {
    std::set<int> labels;
    Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
    for (int i = blob; i < 90; i += 3) {
      labels.insert(c.labels[static_cast<std::size_t>(i)]);
      mean += points.row(i) / 30.0;
    }
    ASSERT_EQ(labels.size(), 1u) << "blob " << blob << " was split";
    EXPECT_TRUE(c.centres.row(*labels.begin()).isApprox(mean, 1e-12));
  }
  const Clustering again = kmeans(points, 3, 11);
  EXPECT_EQ(again.labels, c.labels);
}

TEST(SynthKmeansTest, MoreClustersThanPointsGivesOnePerPoint) {
  Points3 points(2, 3);
  points << 0, 0, 0, 1, 1, 1;
  const Clustering c = kmeans(points, 26, 1);
  EXPECT_EQ(c.centres.rows(), 2);
  EXPECT_NE(c.labels[0], c.labels[1]);
  EXPECT_THROW(kmeans(points, 0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace grip::synth
