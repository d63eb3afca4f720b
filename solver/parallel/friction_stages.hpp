#pragma once
// The data-parallel engine's friction stage, one source for every launcher (launch.hpp): per
// lagged friction contact of a whole batch, IPC's friction potential mu lambda f0(|u|), its
// 12-vector gradient and its 12x12 Hessian in the four vertices' positions, u = T^T (x - x0)
// the tangential displacement over the step (kernels/friction_potential.hpp, as the CPU
// engine's FrictionTerm evaluates them). The Hessian is positive semi-definite as it stands,
// so no projection. The contacts are frozen at the friction lag on the host (FrictionLag), as
// the CPU engine freezes them; mapping positions to DOFs is a later stage.
#include <Eigen/Core>
#include <vector>

#include "solver/kernels/friction_potential.hpp"
#include "solver/kernels/hd.hpp"

namespace grip::solver::parallel {

// What the stage reads of a batch's friction contacts: raw pointers into host or device memory.
struct FrictionBuffers {
  int count = 0;
  const int* vertex = nullptr;        // 4 per contact: collision vertices in the batch
  const double* tangent = nullptr;    // 24 per contact: its 12x2 tangent operator, by column
  const double* mu_lambda = nullptr;  // per contact: mu times the lagged normal force, N
  const int* environment = nullptr;   // per contact
  const double* eps = nullptr;        // per environment: eps_v h, m
};

// A batch's lagged friction contacts, host-built: each environment's after the previous one's,
// its collision vertices numbered after the previous environments' (vertex_begin).
class FrictionContacts {
 public:
  // Starts the next environment, with its collision vertex count and eps_v h.
  void begin_environment(int vertex_count, double eps);
  // A contact of the environment begun last: its four collision vertices (the environment's
  // own numbering), tangent operator and mu lambda.
  void add(const int vertex[4], const Eigen::Matrix<double, 12, 2>& tangent, double mu_lambda);

  int environment_count() const { return static_cast<int>(eps_.size()); }
  const std::vector<int>& vertex_begin() const { return vertex_begin_; }
  const std::vector<int>& contact_begin() const { return contact_begin_; }
  FrictionBuffers buffers() const;

  const std::vector<int>& vertex() const { return vertex_; }
  const std::vector<double>& tangent() const { return tangent_; }
  const std::vector<double>& mu_lambda() const { return mu_lambda_; }
  const std::vector<int>& environment() const { return environment_; }
  const std::vector<double>& eps() const { return eps_; }

 private:
  std::vector<int> vertex_begin_{0};
  std::vector<int> contact_begin_{0};
  std::vector<int> vertex_;
  std::vector<double> tangent_;
  std::vector<double> mu_lambda_;
  std::vector<int> environment_;
  std::vector<double> eps_;
};

struct FrictionStage {
  FrictionBuffers contacts;
  const double* positions = nullptr;        // 3 per collision vertex of the batch, now
  const double* start_positions = nullptr;  // the same at the step's start
  double* energy = nullptr;                 // per contact
  double* gradient = nullptr;               // 12 per contact; null: the energy alone
  double* hessian = nullptr;                // 144 per contact, column-major; null: not wanted

  GRIP_HD void operator()(int k) const {
    Eigen::Matrix<double, 12, 1> dx;
    for (int c = 0; c < 4; ++c) {
      const int v = contacts.vertex[4 * k + c];
      for (int d = 0; d < 3; ++d) dx[3 * c + d] = positions[3 * v + d] - start_positions[3 * v + d];
    }
    const Eigen::Map<const Eigen::Matrix<double, 12, 2>> tangent(contacts.tangent + 24 * k);
    const Eigen::Matrix<double, 12, 2> t = tangent;
    const double mu_lambda = contacts.mu_lambda[k];
    const double eps = contacts.eps[contacts.environment[k]];
    energy[k] = kernels::friction_potential<4>(dx, t, mu_lambda, eps);
    if (gradient == nullptr) return;
    Eigen::Map<Eigen::Matrix<double, 12, 1>> g(gradient + 12 * k);
    g = kernels::friction_potential_gradient<4>(dx, t, mu_lambda, eps);
    if (hessian == nullptr) return;
    Eigen::Map<Eigen::Matrix<double, 12, 12>> h(hessian + 144 * k);
    h = kernels::friction_potential_hessian<4>(dx, t, mu_lambda, eps);
  }
};

}  // namespace grip::solver::parallel
