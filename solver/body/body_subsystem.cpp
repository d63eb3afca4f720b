#include "solver/body/body_subsystem.hpp"

#include <Eigen/SVD>
#include <stdexcept>

namespace grip::solver {

int BodySubsystem::add(const BodyDescription& description, int body) {
  build(description);
  body_.push_back(body);
  dof_offset_.push_back(0);
  return size() - 1;
}

Vertices BodySubsystem::rest_vertices(int i) const {
  Vertices rest(vertex_count(i), 3);
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    rest.row(v) = rest_vertex(i, static_cast<int>(v)).transpose();
  }
  return rest;
}

void invalid_body(const BodyDescription& body, const std::string& problem) {
  throw std::invalid_argument("body '" + body.name + "': " + problem);
}

Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& m) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

}  // namespace grip::solver
