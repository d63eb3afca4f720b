#include "src/synth/hand_clearance_fix.hpp"

#include <algorithm>

#include <Eigen/Cholesky>

namespace grip::synth {

std::optional<FixedHand> fix_hand_clearance(const PreparedHand& hand, const PreparedObject& object,
                                            HandState state, const ClearanceFixParams& params) {
  const grippers::KinematicTree& tree = hand.kinematics();
  const double target = params.d_hat + params.margin;
  const double cutoff = 4.0 * params.d_hat;
  for (int iteration = 0; iteration <= params.iterations; ++iteration) {
    const std::vector<Eigen::Isometry3d> poses = tree.link_poses(state.base, state.joints);
    int worst = -1;
    double worst_clearance = cutoff;
    for (int l = 0; l < hand.link_count(); ++l) {
      if (!hand.link_distance(l)) continue;
      const double c = object.clearance(hand.posed_link(poses, l), cutoff);
      if (c < worst_clearance) worst_clearance = c, worst = l;
    }
    if (worst_clearance >= target) return FixedHand{state, worst_clearance};
    if (iteration == params.iterations) break;

    // The link vertex that needs the longest move to reach the target distance.
    const geometry::SurfaceMesh link = hand.posed_link(poses, worst);
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    double need = -1e300;
    for (int v = 0; v < link.vertices.rows(); ++v) {
      const Eigen::Vector3d y = link.vertices.row(v).transpose();
      const double v_need = target + object.signed_distance()(y);  // signed: positive inside
      if (v_need > need) need = v_need, point = y;
    }
    const TriangleTree::Closest closest = object.tree().closest(point);
    const Eigen::Vector3d move =
        object.tree().face_normal(closest.face) * (std::max(need, 0.0) + 0.5 * params.margin);

    const Eigen::Vector3d local = poses[static_cast<std::size_t>(worst)].inverse() * point;
    const Eigen::Matrix<double, 3, Eigen::Dynamic> jacobian =
        tree.point_jacobian(poses, worst, local).topRows<3>();
    Eigen::Vector3d reached = Eigen::Vector3d::Zero();
    if (jacobian.norm() > 0.0) {
      const Eigen::Matrix3d system = jacobian * jacobian.transpose() +
                                     params.damping * params.damping * Eigen::Matrix3d::Identity();
      const Eigen::VectorXd q =
          tree.clamp_to_limits(state.joints + jacobian.transpose() * system.ldlt().solve(move));
      reached = jacobian * (q - state.joints);
      state.joints = q;
    }
    // What the joints cannot do (the palm, a joint at its limit) the whole hand does.
    if (reached.dot(move) < 0.5 * move.squaredNorm()) {
      state.base.translation() += move - reached.dot(move) / move.squaredNorm() * move;
    }
  }
  return std::nullopt;
}

}  // namespace grip::synth
