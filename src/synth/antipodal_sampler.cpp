#include "src/synth/antipodal_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "src/geometry/surface_sampling.hpp"
#include "src/synth/candidate_random.hpp"
#include "src/synth/surface_frames.hpp"

namespace grip::synth {
namespace {

constexpr std::uint32_t kCloudStream = 11;
constexpr std::uint32_t kAttemptStream = 12;

struct Box {
  Eigen::Vector3d lower;
  Eigen::Vector3d upper;
  bool contains(const Eigen::Vector3d& p) const {
    return (p.array() >= lower.array()).all() && (p.array() <= upper.array()).all();
  }
};

// The quick collision model in the gripper frame at one opening: two finger boxes and the
// carriage behind the mounts.
struct GripperBoxes {
  Box positive, negative, body;

  GripperBoxes(const Box& finger, double opening, double body_depth) {
    const double half = 0.5 * opening;
    positive = {finger.lower + Eigen::Vector3d(0, half, 0),
                finger.upper + Eigen::Vector3d(0, half, 0)};
    // The negative finger is the positive one turned half a turn about z.
    negative = {Eigen::Vector3d(-finger.upper.x(), -half - finger.upper.y(), finger.lower.z()),
                Eigen::Vector3d(-finger.lower.x(), -half - finger.lower.y(), finger.upper.z())};
    body = {positive.lower.cwiseMin(negative.lower), positive.upper.cwiseMax(negative.upper)};
    body.upper.z() = finger.lower.z();
    body.lower.z() = finger.lower.z() - body_depth;
  }

  bool collides(const Eigen::Vector3d& p) const {
    return positive.contains(p) || negative.contains(p) || body.contains(p);
  }
};

}  // namespace

geometry::SurfaceMesh posed_parallel_surface(const grippers::ParallelGripper& gripper,
                                             const HandGrasp& hand) {
  geometry::SurfaceMesh mesh = gripper.surface(hand.joints(0));
  for (int v = 0; v < mesh.vertices.rows(); ++v) {
    mesh.vertices.row(v) = (hand.pose * Eigen::Vector3d(mesh.vertices.row(v))).transpose();
  }
  return mesh;
}

SynthesisResult sample_antipodal_grasps(const PreparedObject& object,
                                        const grippers::ParallelGripper& gripper,
                                        grippers::GripperKind kind, const AntipodalParams& params,
                                        std::uint64_t seed, int count) {
  if (kind != grippers::GripperKind::kDescribed && grippers::gripper_type(kind).is_hand()) {
    throw std::invalid_argument("sample_antipodal_grasps: the " +
                                grippers::gripper_type(kind).name +
                                " hand is not a parallel gripper");
  }
  const geometry::SurfaceSamples cloud = geometry::sample_surface(
      object.surface(), params.cloud_points, CandidateRandom(seed, kCloudStream, 0).below(1 << 30));
  const SurfaceFrames frames(cloud, params.frame_radius);

  const Box finger{gripper.finger_surface.vertices.colwise().minCoeff().transpose(),
                   gripper.finger_surface.vertices.colwise().maxCoeff().transpose()};
  const double length = finger.upper.z();
  const double cos_cone = std::cos(std::atan(params.friction));
  const double target = params.d_hat + params.margin;
  const GripperBoxes open_boxes(finger, gripper.max_opening, params.body_depth);

  const auto attempt = [&](std::int64_t index) -> AttemptOutcome {
    // Consecutive attempts share a surface point and turn about its curvature axis.
    CandidateRandom random(seed, kAttemptStream,
                           static_cast<std::uint64_t>(index / params.rotations));
    const SurfaceFrame frame = frames.at(random.below(static_cast<int>(cloud.points.rows())));
    const double angle =
        std::numbers::pi * (-0.5 + double(index % params.rotations) / params.rotations);
    const Eigen::AngleAxisd turn(angle, frame.curvature_axis);
    const Eigen::Vector3d approach = turn * (-frame.normal);
    const Eigen::Vector3d closing = turn * frame.binormal;
    Eigen::Matrix3d rotation;
    rotation.col(0) = closing.cross(approach);
    rotation.col(1) = closing;
    rotation.col(2) = approach;

    // Cloud in the gripper frame with the surface point on the finger tips' plane (depth 0).
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> local(cloud.points.rows(), 3);
    for (int i = 0; i < cloud.points.rows(); ++i) {
      local.row(i) =
          (rotation.transpose() * (cloud.points.row(i).transpose() - frame.point)).transpose();
      local(i, 2) += length;
    }
    // Deepen along the approach while the open gripper stays collision-free.
    double depth = -1.0;
    for (double d = 0.0; d <= length - params.min_inset + 1e-12; d += params.depth_step) {
      bool free = true;
      for (int i = 0; i < local.rows() && free; ++i) {
        free = !open_boxes.collides(Eigen::Vector3d(local(i, 0), local(i, 1), local(i, 2) - d));
      }
      if (!free) break;
      depth = d;
    }
    if (depth < 0.0) return {std::nullopt, "collision at the first approach step"};
    if (depth < gripper.min_grasp_depth) {
      return {std::nullopt, "too shallow for the fingers to reach the grip force"};
    }

    // The object between the open fingers decides the centring and the opening.
    double y_min = 1e300, y_max = -1e300;
    std::vector<int> between;
    for (int i = 0; i < local.rows(); ++i) {
      const Eigen::Vector3d p(local(i, 0), local(i, 1), local(i, 2) - depth);
      if (p.x() >= finger.lower.x() && p.x() <= finger.upper.x() && p.z() >= finger.lower.z() &&
          p.z() <= finger.upper.z() && std::abs(p.y()) < 0.5 * gripper.max_opening) {
        between.push_back(i);
        y_min = std::min(y_min, p.y());
        y_max = std::max(y_max, p.y());
      }
    }
    if (between.empty()) return {std::nullopt, "nothing between the fingers"};
    const double width = y_max - y_min;
    const double opening = std::max(gripper.min_opening, width + 2.0 * params.gap);
    if (opening > gripper.max_opening) return {std::nullopt, "too wide"};

    // Friction-cone antipodality: a contact on each jaw side whose normal lies in the cone
    // about the closing axis (outward normals face the jaws: -y at y_min, +y at y_max).
    int left = -1, right = -1;
    double left_cos = -2.0, right_cos = -2.0;
    for (const int i : between) {
      const double c = cloud.normals.row(i).dot(closing);
      if (local(i, 1) <= y_min + params.contact_band && -c > left_cos) left_cos = -c, left = i;
      if (local(i, 1) >= y_max - params.contact_band && c > right_cos) right_cos = c, right = i;
    }
    if (left < 0 || right < 0 || left_cos < cos_cone || right_cos < cos_cone) {
      return {std::nullopt, "not antipodal"};
    }

    HandGrasp hand;
    hand.pose.linear() = rotation;
    hand.pose.translation() =
        frame.point - approach * (length - depth) + closing * (0.5 * (y_min + y_max));
    hand.joints = Eigen::VectorXd::Constant(1, opening);
    hand.contacts.resize(2, 3);
    hand.contact_normals.resize(2, 3);
    hand.contacts.row(0) = cloud.points.row(left);
    hand.contacts.row(1) = cloud.points.row(right);
    hand.contact_normals.row(0) = cloud.normals.row(left);
    hand.contact_normals.row(1) = cloud.normals.row(right);

    // The exact test: every finger triangle keeps d_hat + margin from every object triangle.
    const double clearance =
        object.clearance(posed_parallel_surface(gripper, hand), std::max(target, 2.0 * params.gap));
    if (clearance < target) return {std::nullopt, "fingers within d_hat + margin of the object"};

    Candidate candidate;
    candidate.gripper = kind;
    candidate.hands.push_back(std::move(hand));
    candidate.energies = {{"antipodal_angle", std::acos(std::min(left_cos, right_cos))},
                          {"depth", depth},
                          {"width", width}};
    candidate.min_distance = clearance;
    return {std::move(candidate), ""};
  };
  return run_attempts(count, params.max_attempts_per_candidate * std::max(count, 1), params.block,
                      attempt);
}

}  // namespace grip::synth
