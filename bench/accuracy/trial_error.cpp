#include "bench/accuracy/trial_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>
#include <Eigen/SVD>

namespace grip::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Row-major 3x4 [A | t] at `offset`.
Eigen::Matrix<double, 3, 4> pose_at(const std::vector<double>& poses, std::size_t offset) {
  Eigen::Matrix<double, 3, 4> m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = poses[offset + 4 * r + c];
  return m;
}

// The object's pose in the gripper frame: its origin and its rotation (the nearest rotation to
// the affine body's matrix, or to a soft object's best fit).
struct RelativePose {
  Eigen::Vector3d origin;
  Eigen::Matrix3d rotation;
};

RelativePose relative_pose(const io::TrajectoryRecord& t, std::size_t frame) {
  const Eigen::Matrix<double, 3, 4> gripper = pose_at(t.hand_poses, 12 * frame);
  const Eigen::Matrix<double, 3, 4> object = pose_at(t.object_poses, 12 * frame);
  const Eigen::Matrix3d r_gripper = gripper.leftCols<3>();
  const Eigen::Matrix3d a = r_gripper.transpose() * object.leftCols<3>();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return {r_gripper.transpose() * (object.col(3) - gripper.col(3)),
          svd.matrixU() * d * svd.matrixV().transpose()};
}

// Largest distance between `count` vertices from vertex `first_a` of `a` and `first_b` of `b`
// (x, y, z per vertex).
double largest_distance(const std::vector<float>& a, std::size_t first_a,
                        const std::vector<float>& b, std::size_t first_b, std::size_t count) {
  double largest = 0;
  for (std::size_t v = 0; v < count; ++v) {
    const std::size_t ia = 3 * (first_a + v), ib = 3 * (first_b + v);
    const Eigen::Vector3d d(a[ia] - b[ib], a[ia + 1] - b[ib + 1], a[ia + 2] - b[ib + 2]);
    largest = std::max(largest, d.norm());
  }
  return largest;
}

void add(double value, double& sum, int& count) {
  if (std::isnan(value)) return;
  sum += value;
  ++count;
}

}  // namespace

bool held(const io::CandidateRecord& record, const trial::TrialParameters& judge) {
  if (record.failure != io::FailureKind::kNone && record.failure != io::FailureKind::kDisplaced)
    return false;
  return !trial::slipped_beyond_threshold(judge, record.displacement, record.phase_seconds);
}

TrialError trial_error(const io::CandidateResult& run, const io::CandidateResult& reference,
                       int frames, const trial::TrialParameters& judge) {
  TrialError error;
  error.verdict_agrees = held(run.record, judge) == held(reference.record, judge);
  error.slip = 0;
  for (int phase = 0; phase < 6; ++phase) {
    const double a = run.record.displacement[phase], b = reference.record.displacement[phase];
    if (std::isnan(a) && std::isnan(b)) continue;
    error.slip = std::max(error.slip, std::isnan(a) ? b : std::isnan(b) ? a : std::abs(a - b));
  }
  if (!run.trajectory || !reference.trajectory) {
    error.translation = error.rotation = error.vertices = kNaN;
    return error;
  }
  const io::TrajectoryRecord &a = *run.trajectory, &b = *reference.trajectory;
  const std::size_t frames_a = a.object_poses.size() / 12, frames_b = b.object_poses.size() / 12;
  const auto n = static_cast<std::size_t>(frames);
  if (frames_a < n || frames_b < n) {
    throw std::invalid_argument("trial_error: a trajectory holds fewer frames than compared");
  }
  const std::size_t object_n = a.object_vertices.size() / 3 / frames_a;
  const std::size_t gripper_n = a.gripper_vertices.size() / 3 / frames_a;
  const bool same_meshes = object_n == b.object_vertices.size() / 3 / frames_b &&
                           gripper_n == b.gripper_vertices.size() / 3 / frames_b;
  error.translation = error.rotation = 0;
  error.vertices = same_meshes ? 0 : kNaN;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t fa = frames_a - n + k, fb = frames_b - n + k;
    const RelativePose pa = relative_pose(a, fa), pb = relative_pose(b, fb);
    error.translation = std::max(error.translation, (pa.origin - pb.origin).norm());
    error.rotation =
        std::max(error.rotation, Eigen::AngleAxisd(pa.rotation.transpose() * pb.rotation).angle());
    if (!same_meshes) continue;
    error.vertices = std::max({error.vertices,
                               largest_distance(a.object_vertices, fa * object_n, b.object_vertices,
                                                fb * object_n, object_n),
                               largest_distance(a.gripper_vertices, fa * gripper_n,
                                                b.gripper_vertices, fb * gripper_n, gripper_n)});
  }
  return error;
}

RunError run_error(const std::vector<trial::TrialOutcome>& run,
                   const std::vector<trial::TrialOutcome>& reference, int frames,
                   const trial::TrialParameters& judge) {
  if (run.size() != reference.size()) {
    throw std::invalid_argument("run_error: the run and its reference differ in candidates");
  }
  RunError error;
  error.candidates = static_cast<int>(run.size());
  double sums[4] = {0, 0, 0, 0};
  int counts[4] = {0, 0, 0, 0};
  for (std::size_t k = 0; k < run.size(); ++k) {
    const TrialError e = trial_error(run[k].result, reference[k].result, frames, judge);
    add(e.translation, sums[0], counts[0]);
    add(e.rotation, sums[1], counts[1]);
    add(e.slip, sums[2], counts[2]);
    add(e.vertices, sums[3], counts[3]);
    error.agreeing += e.verdict_agrees;
  }
  const auto mean = [&](int i) { return counts[i] ? sums[i] / counts[i] : kNaN; };
  error.translation = mean(0);
  error.rotation = mean(1);
  error.slip = mean(2);
  error.vertices = mean(3);
  return error;
}

}  // namespace grip::bench
