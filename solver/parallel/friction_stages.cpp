#include "solver/parallel/friction_stages.hpp"

#include <stdexcept>

namespace grip::solver::parallel {

void FrictionContacts::begin_environment(int vertex_count, double eps) {
  vertex_begin_.push_back(vertex_begin_.back() + vertex_count);
  contact_begin_.push_back(contact_begin_.back());
  eps_.push_back(eps);
}

void FrictionContacts::add(const int vertex[4], const Eigen::Matrix<double, 12, 2>& tangent,
                           double mu_lambda) {
  if (environment_count() == 0) {
    throw std::logic_error("FrictionContacts::add before an environment");
  }
  const int e = environment_count() - 1;
  for (int c = 0; c < 4; ++c) vertex_.push_back(vertex_begin_[e] + vertex[c]);
  tangent_.insert(tangent_.end(), tangent.data(), tangent.data() + 24);
  mu_lambda_.push_back(mu_lambda);
  environment_.push_back(e);
  ++contact_begin_.back();
}

FrictionBuffers FrictionContacts::buffers() const {
  return {static_cast<int>(environment_.size()),
          vertex_.data(),
          tangent_.data(),
          mu_lambda_.data(),
          environment_.data(),
          eps_.data()};
}

}  // namespace grip::solver::parallel
