#pragma once
// The commit model's constants fitted to measured commits: least squares of
// seconds = latency + per_log2 log2(ranks) + bytes / bandwidth, no constant below zero.
#include <vector>

#include "bench/scale/farm_model.hpp"

namespace grip::bench {

struct CommitPoint {
  int ranks = 1;
  double bytes = 0;
  double seconds = 0;
};

// Needs points at two rank counts and two byte counts for every term; a term the points cannot
// tell apart from zero (or that fits below zero) is left at zero and the others refitted.
CommitModel fit_commit_model(const std::vector<CommitPoint>& points);
// A unit's commit, no collective in it: seconds = latency + bytes / bandwidth over all points
// whatever their rank count (a slope that fits below zero is dropped: unlimited bandwidth).
CommitModel fit_unit_commit_model(const std::vector<CommitPoint>& points);

}  // namespace grip::bench
