#include "src/synth/hand_energy.hpp"

#include <cmath>

namespace grip::synth {
namespace {

// Accumulates dE/d(base translation, base rotation, joints) from gradients at points moving
// with links and from torques on links.
class GradientAccumulator {
 public:
  GradientAccumulator(const grippers::KinematicTree& tree,
                      const std::vector<Eigen::Isometry3d>& poses, const Eigen::Vector3d& origin,
                      Eigen::VectorXd* gradient)
      : tree_(tree), poses_(poses), origin_(origin), gradient_(gradient) {}

  // dE/dy = g at world point y carried by `link`.
  void point(int link, const Eigen::Vector3d& y, const Eigen::Vector3d& g) {
    if (!gradient_) return;
    gradient_->segment<3>(0) += g;
    gradient_->segment<3>(3) += (y - origin_).cross(g);
    const Eigen::Vector3d local = poses_[static_cast<std::size_t>(link)].inverse() * y;
    gradient_->tail(tree_.dof_count()) +=
        tree_.point_jacobian(poses_, link, local).topRows<3>().transpose() * g;
  }

  // dE/d(omega) = tau for the world angular velocity omega of `link`.
  void torque(int link, const Eigen::Vector3d& tau) {
    if (!gradient_) return;
    gradient_->segment<3>(3) += tau;
    gradient_->tail(tree_.dof_count()) +=
        tree_.point_jacobian(poses_, link, Eigen::Vector3d::Zero()).bottomRows<3>().transpose() *
        tau;
  }

 private:
  const grippers::KinematicTree& tree_;
  const std::vector<Eigen::Isometry3d>& poses_;
  Eigen::Vector3d origin_;
  Eigen::VectorXd* gradient_;
};

}  // namespace

HandEnergy::HandEnergy(const PreparedHand& hand, const PreparedObject& object,
                       const geometry::Vertices& object_points, HandEnergyWeights weights)
    : hand_(hand), object_(object), object_points_(object_points), weights_(weights) {}

HandState HandEnergy::moved(const HandState& state, const Eigen::VectorXd& step) {
  HandState next = state;
  next.base.translation() += step.segment<3>(0);
  const Eigen::Vector3d w = step.segment<3>(3);
  if (w.norm() > 0.0) {
    next.base.linear() =
        Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix() * state.base.linear();
  }
  next.joints += step.tail(state.joints.size());
  return next;
}

HandEnergyTerms HandEnergy::evaluate(const HandState& state, Eigen::VectorXd* gradient) const {
  const grippers::KinematicTree& tree = hand_.kinematics();
  const std::vector<Eigen::Isometry3d> poses = tree.link_poses(state.base, state.joints);
  const int dofs = tree.dof_count();
  Eigen::VectorXd g_fc, g_dis, g_pen, g_spen, g_normal;
  for (Eigen::VectorXd* g : {&g_fc, &g_dis, &g_pen, &g_spen, &g_normal}) g->setZero(6 + dofs);
  const bool want = gradient != nullptr;
  const Eigen::Vector3d origin = state.base.translation();
  GradientAccumulator fc(tree, poses, origin, want ? &g_fc : nullptr);
  GradientAccumulator dis(tree, poses, origin, want ? &g_dis : nullptr);
  GradientAccumulator pen(tree, poses, origin, want ? &g_pen : nullptr);
  GradientAccumulator spen(tree, poses, origin, want ? &g_spen : nullptr);
  GradientAccumulator normal(tree, poses, origin, want ? &g_normal : nullptr);
  HandEnergyTerms terms;

  // Contacts: distance to the object, normal alignment, and the force-closure wrench (torques
  // about the object's centroid).
  const auto n_c = static_cast<int>(state.contacts.size());
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> points(n_c, 3), normals(n_c, 3);
  std::vector<int> links(static_cast<std::size_t>(n_c));
  std::vector<Eigen::Vector3d> world(static_cast<std::size_t>(n_c));
  for (int i = 0; i < n_c; ++i) {
    const PreparedHand::LinkPoint& c =
        hand_.contacts()[static_cast<std::size_t>(state.contacts[static_cast<std::size_t>(i)])];
    const Eigen::Isometry3d& pose = poses[static_cast<std::size_t>(c.link)];
    const Eigen::Vector3d x = pose * c.position;
    const Eigen::Vector3d n_h = pose.linear() * c.normal;
    const TriangleTree::Closest closest = object_.tree().closest(x);
    const Eigen::Vector3d n_o = object_.tree().face_normal(closest.face);
    points.row(i) = (x - object_.centroid()).transpose();
    world[static_cast<std::size_t>(i)] = x;
    normals.row(i) = n_o.transpose();
    links[static_cast<std::size_t>(i)] = c.link;
    terms.dis += closest.distance;
    if (closest.distance > 0.0) dis.point(c.link, x, (x - closest.point) / closest.distance);
    const double a = n_h.dot(n_o) + 1.0;
    terms.normal += a * a;
    normal.torque(c.link, 2.0 * a * n_h.cross(n_o));
  }
  terms.fc = force_closure_error(points, normals);
  if (terms.fc > 0.0) {
    Eigen::Vector3d torque_sum = Eigen::Vector3d::Zero();
    for (int i = 0; i < n_c; ++i) {
      torque_sum += points.row(i).transpose().cross(normals.row(i).transpose());
    }
    for (int i = 0; i < n_c; ++i) {
      fc.point(links[static_cast<std::size_t>(i)], world[static_cast<std::size_t>(i)],
               normals.row(i).transpose().cross(torque_sum) / terms.fc);
    }
  }

  // Object points inside links: the link's exact signed distance, positive inside. A fixed
  // world point p seen from a link moving with velocity v(p) moves by -v(p) in its frame.
  for (int l = 0; l < hand_.link_count(); ++l) {
    const geometry::SignedDistance* sd = hand_.link_distance(l);
    if (!sd) continue;
    const Eigen::Isometry3d& pose = poses[static_cast<std::size_t>(l)];
    const Eigen::Isometry3d inverse = pose.inverse();
    const Eigen::Matrix<double, 2, 3>& box = hand_.link_box(l);
    for (int i = 0; i < object_points_.rows(); ++i) {
      const Eigen::Vector3d p = object_points_.row(i).transpose();
      const Eigen::Vector3d local = inverse * p;
      if ((local.transpose().array() < box.row(0).array()).any() ||
          (local.transpose().array() > box.row(1).array()).any()) {
        continue;
      }
      const double depth = (*sd)(local);
      if (depth <= 0.0) continue;
      terms.pen += depth;
      if (want) {
        const Eigen::Vector3d inward = (local - sd->closest_point(local)).normalized();
        pen.point(l, p, -(pose.linear() * inward));
      }
    }
  }

  // Keypoint spheres of links that may not touch.
  std::vector<Eigen::Vector3d> centres;
  for (const PreparedHand::LinkPoint& k : hand_.keypoints()) {
    centres.push_back(poses[static_cast<std::size_t>(k.link)] * k.position);
  }
  for (const auto& [a, b] : hand_.keypoint_pairs()) {
    const PreparedHand::LinkPoint& ka = hand_.keypoints()[static_cast<std::size_t>(a)];
    const PreparedHand::LinkPoint& kb = hand_.keypoints()[static_cast<std::size_t>(b)];
    const Eigen::Vector3d d =
        centres[static_cast<std::size_t>(a)] - centres[static_cast<std::size_t>(b)];
    const double overlap = ka.radius + kb.radius - d.norm();
    if (overlap <= 0.0) continue;
    terms.spen += overlap;
    const Eigen::Vector3d u = d.normalized();
    spen.point(ka.link, centres[static_cast<std::size_t>(a)], -u);
    spen.point(kb.link, centres[static_cast<std::size_t>(b)], u);
  }

  Eigen::VectorXd g_joints;
  terms.joints = joint_limit_energy(state.joints, tree.lower_limits(), tree.upper_limits(),
                                    want ? &g_joints : nullptr);
  const HandEnergyWeights& w = weights_;
  terms.total = w.fc * terms.fc + w.dis * terms.dis + w.pen * terms.pen + w.spen * terms.spen +
                w.joints * terms.joints + w.normal * terms.normal;
  if (want) {
    *gradient = w.fc * g_fc + w.dis * g_dis + w.pen * g_pen + w.spen * g_spen + w.normal * g_normal;
    gradient->tail(dofs) += w.joints * g_joints;
  }
  return terms;
}

double joint_limit_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& lower,
                          const Eigen::VectorXd& upper, Eigen::VectorXd* gradient) {
  double energy = 0.0;
  if (gradient) gradient->setZero(q.size());
  for (int i = 0; i < q.size(); ++i) {
    if (q(i) > upper(i)) {
      energy += q(i) - upper(i);
      if (gradient) (*gradient)(i) = 1.0;
    } else if (q(i) < lower(i)) {
      energy += lower(i) - q(i);
      if (gradient) (*gradient)(i) = -1.0;
    }
  }
  return energy;
}

double force_closure_error(
    const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& points,
    const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& normals) {
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  for (int i = 0; i < points.rows(); ++i) {
    force += normals.row(i).transpose();
    torque += points.row(i).transpose().cross(normals.row(i).transpose());
  }
  return std::sqrt(force.squaredNorm() + torque.squaredNorm());
}

}  // namespace grip::synth
