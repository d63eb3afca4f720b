#pragma once
// The data-parallel engine's barrier stage, one source for every launcher (launch.hpp): per
// contact pair of a whole batch, IPC's barrier, its 12-vector gradient and its 12x12 Hessian
// in the four vertices' positions (kernels/contact_barrier.hpp, as the CPU engine's
// BarrierTerm evaluates them), the Hessian PSD-projected by Jacobi rotations on every launcher
// (kernels/jacobi_psd_projection.hpp; the CPU engine's Eigen solver is host-only). Mapping
// positions to DOFs (affine bodies' Jacobians, pins) is a later stage.
#include <Eigen/Core>
#include <vector>

#include "solver/kernels/contact_barrier.hpp"
#include "solver/kernels/hd.hpp"
#include "solver/kernels/jacobi_psd_projection.hpp"

namespace grip::solver::parallel {

// What the stage reads of a batch's contact pairs: raw pointers into host or device memory.
struct PairBuffers {
  int count = 0;
  const int* vertex = nullptr;               // 4 per pair: collision vertices in the batch
  const unsigned char* edge_edge = nullptr;  // per pair: 1 edge-edge, 0 point-triangle
  const double* mollifier_eps = nullptr;     // per pair (edge-edge)
  const int* environment = nullptr;          // per pair
  const double* d_hat = nullptr;             // per environment
  const double* kappa = nullptr;             // per environment
};

// A batch's contact pairs, host-built: each environment's pairs after the previous one's, its
// collision vertices numbered after the previous environments' (vertex_begin).
class ContactPairs {
 public:
  // Starts the next environment, with its collision vertex count, d_hat and kappa.
  void begin_environment(int vertex_count, double d_hat, double kappa);
  // A pair of the environment begun last: its four collision vertices (the environment's own
  // numbering; (p, t0, t1, t2) or (ea0, ea1, eb0, eb1)).
  void add(bool edge_edge, const int vertex[4], double mollifier_eps);

  int environment_count() const { return static_cast<int>(d_hat_.size()); }
  const std::vector<int>& vertex_begin() const { return vertex_begin_; }
  const std::vector<int>& pair_begin() const { return pair_begin_; }
  PairBuffers pairs() const;

  const std::vector<int>& vertex() const { return vertex_; }
  const std::vector<unsigned char>& edge_edge() const { return edge_edge_; }
  const std::vector<double>& mollifier_eps() const { return mollifier_eps_; }
  const std::vector<int>& environment() const { return environment_; }
  const std::vector<double>& d_hat() const { return d_hat_; }
  const std::vector<double>& kappa() const { return kappa_; }

 private:
  std::vector<int> vertex_begin_{0};
  std::vector<int> pair_begin_{0};
  std::vector<int> vertex_;
  std::vector<unsigned char> edge_edge_;
  std::vector<double> mollifier_eps_;
  std::vector<int> environment_;
  std::vector<double> d_hat_;
  std::vector<double> kappa_;
};

struct BarrierStage {
  PairBuffers pairs;
  const double* positions = nullptr;  // 3 per collision vertex of the batch
  // Per environment: 1 where the Hessian stays as it is, else it is PSD-projected (projected
  // Newton); null: projected in every environment.
  const unsigned char* exact = nullptr;
  double* energy = nullptr;    // per pair
  double* gradient = nullptr;  // 12 per pair; null: the energy alone (a line search's)
  double* hessian = nullptr;   // 144 per pair, column-major; null: not wanted

  GRIP_HD void operator()(int k) const {
    Eigen::Vector3d x[4];
    for (int c = 0; c < 4; ++c) {
      const int v = pairs.vertex[4 * k + c];
      x[c] = Eigen::Vector3d(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    }
    const int e = pairs.environment[k];
    if (gradient == nullptr) {
      energy[k] = kernels::contact_barrier_value(pairs.edge_edge[k] != 0, pairs.mollifier_eps[k], x,
                                                 pairs.d_hat[e], pairs.kappa[e]);
      return;
    }
    const kernels::ContactBarrier b =
        kernels::contact_barrier(pairs.edge_edge[k] != 0, pairs.mollifier_eps[k], x, pairs.d_hat[e],
                                 pairs.kappa[e], hessian != nullptr);
    energy[k] = b.value;
    Eigen::Map<Eigen::Matrix<double, 12, 1>> g(gradient + 12 * k);
    g = b.gradient;
    if (hessian == nullptr) return;
    Eigen::Map<Eigen::Matrix<double, 12, 12>> h(hessian + 144 * k);
    const bool project = exact == nullptr || exact[e] == 0;
    h = project ? kernels::project_to_psd_jacobi<12>(b.hessian) : b.hessian;
  }
};

}  // namespace grip::solver::parallel
