#include "solver/parallel/contact_stages.hpp"

#include <stdexcept>

namespace grip::solver::parallel {

void ContactPairs::begin_environment(int vertex_count, double d_hat, double kappa) {
  vertex_begin_.push_back(vertex_begin_.back() + vertex_count);
  pair_begin_.push_back(pair_begin_.back());
  d_hat_.push_back(d_hat);
  kappa_.push_back(kappa);
}

void ContactPairs::add(bool edge_edge, const int vertex[4], double mollifier_eps) {
  if (environment_count() == 0) throw std::logic_error("ContactPairs::add before an environment");
  const int e = environment_count() - 1;
  for (int c = 0; c < 4; ++c) vertex_.push_back(vertex_begin_[e] + vertex[c]);
  edge_edge_.push_back(edge_edge ? 1 : 0);
  mollifier_eps_.push_back(mollifier_eps);
  environment_.push_back(e);
  ++pair_begin_.back();
}

PairBuffers ContactPairs::pairs() const {
  return {static_cast<int>(environment_.size()),
          vertex_.data(),
          edge_edge_.data(),
          mollifier_eps_.data(),
          environment_.data(),
          d_hat_.data(),
          kappa_.data()};
}

}  // namespace grip::solver::parallel
