#include "solver/newton/line_search.hpp"

#include <algorithm>

#include "solver/kernels/accd.hpp"

namespace grip::solver {
namespace {

kernels::AccdResult time_of_impact(const ContactCandidate& c, const Vertices& start,
                                   const Vertices& end, double rescaling) {
  kernels::AccdOptions options;
  options.rescaling = rescaling;
  const auto& v = c.vertex;
  auto s = [&](int i) -> Eigen::Vector3d { return start.row(v[i]); };
  auto e = [&](int i) -> Eigen::Vector3d { return end.row(v[i]); };
  return c.edge_edge
             ? kernels::edge_edge_accd(s(0), s(1), s(2), s(3), e(0), e(1), e(2), e(3), options)
             : kernels::point_triangle_accd(s(0), s(1), s(2), s(3), e(0), e(1), e(2), e(3),
                                            options);
}

}  // namespace

double collision_free_fraction(const std::vector<ContactCandidate>& candidates,
                               const Vertices& start, const Vertices& end, double rescaling) {
  double alpha = 1.0;
  for (const ContactCandidate& c : candidates) {
    const kernels::AccdResult impact = time_of_impact(c, start, end, rescaling);
    if (impact.impact) alpha = std::min(alpha, impact.toi);
  }
  return alpha;
}

bool halve_until_no_inversion(const Model& model, const Eigen::VectorXd& q,
                              const Eigen::VectorXd& p, double& alpha, int& halvings) {
  while (model.min_volume_ratio(q + alpha * p) <= 0.0) {
    alpha *= 0.5;
    ++halvings;
    if (alpha < 1e-12) return false;
  }
  return true;
}

bool armijo(const IncrementalPotential& potential, const Model& model, const StepTargets& targets,
            const std::vector<ContactCandidate>& candidates, const Eigen::VectorXd& q,
            const Eigen::VectorXd& p, double energy, double slope, bool accept_any, double& alpha,
            int& halvings) {
  for (;;) {
    const Eigen::VectorXd trial = q + alpha * p;
    if (potential.energy(trial, collision_positions(model, trial, targets, 1.0), candidates) <=
            energy + 1e-4 * alpha * slope ||
        accept_any) {
      return true;
    }
    alpha *= 0.5;
    ++halvings;
    if (alpha < 1e-12) return false;
  }
}

}  // namespace grip::solver
