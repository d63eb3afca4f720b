#include "src/trial/contact_patch.hpp"

namespace grip::trial {

namespace {

// A patch spreads in two directions when the second singular value of its weighted
// cross-covariance is at least this fraction of the first: its width is then at least about
// 1 % of its length.
constexpr double kSpread = 1e-4;

}  // namespace

void ContactPatch::add(int vertex, const Eigen::Vector3d& settled, double weight) {
  vertices_.push_back({vertex, settled, weight});
}

RigidMotion ContactPatch::motion(const solver::Vertices& x) const {
  RigidMotion motion;
  if (vertices_.empty()) return motion;
  double weight = 0.0;
  Eigen::Vector3d settled_mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Vertex& v : vertices_) {
    weight += v.weight;
    settled_mean += v.weight * v.settled;
    mean += v.weight * x.row(v.index).transpose();
  }
  settled_mean /= weight;
  mean /= weight;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Vertex& v : vertices_) {
    covariance +=
        v.weight * (v.settled - settled_mean) * (x.row(v.index).transpose() - mean).transpose();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d& spread = svd.singularValues();
  if (spread(1) > kSpread * spread(0)) {
    const Eigen::Matrix3d& u = svd.matrixU();
    const Eigen::Matrix3d& v = svd.matrixV();
    Eigen::Matrix3d reflection = Eigen::Matrix3d::Identity();
    reflection(2, 2) = (v * u.transpose()).determinant() < 0.0 ? -1.0 : 1.0;
    motion.rotation = v * reflection * u.transpose();
  }
  motion.translation = mean - motion.rotation * settled_mean;
  return motion;
}

}  // namespace grip::trial
