#pragma once
// The data-parallel friction lag, as the CPU engine's lag_friction (solver/potential/
// friction_lag.hpp) freezes it: of every environment's contact candidates at the lag's
// positions (the broad phase's, within d_hat), each pair with mu > 0 (or any, with
// `at_zero_mu`) that pushes (normal force kappa m |b'(d)| > 0, not near at rest) becomes a
// lagged friction contact: its four vertices, mu lambda and its tangent operator (the contact
// frame's, kernels/contact_frame.hpp). Candidates are flagged, the flags scanned into offsets,
// the contacts written in the candidates' order, each environment's after the previous one's:
// FrictionBuffers' layout, in the batch's collision vertex numbering.
#include <Eigen/Core>

#include "solver/kernels/contact_barrier.hpp"
#include "solver/kernels/contact_frame.hpp"
#include "solver/kernels/hd.hpp"

namespace grip::solver::parallel {

struct FrictionLagBuffers {
  // The candidates: per pair as the broad phase writes them (CandidateBuffers).
  int count = 0;
  const int* vertex = nullptr;  // 4 per pair, the batch's collision vertices
  const unsigned char* edge_edge = nullptr;
  const unsigned char* near_at_rest = nullptr;
  const double* friction = nullptr;  // mu
  const double* mollifier_eps = nullptr;
  const int* environment = nullptr;
  const int* candidate_begin = nullptr;  // environments + 1 offsets
  int environment_count = 0;
  const double* positions = nullptr;  // 3 per collision vertex: the lag's
  const double* d_hat = nullptr;      // per environment
  const double* kappa = nullptr;      // per environment
  bool at_zero_mu = false;            // StepPolicy::friction_terms_at_zero_mu
  // Per candidate: 1 where it becomes a contact, scanned in place into offsets (count + 1);
  // its mu lambda and tangent operator (24, by column) where it does.
  int* keep = nullptr;
  double* mu_lambda = nullptr;
  double* tangent = nullptr;
};

// The contacts written: FrictionBuffers' arrays, sized by the total the scan gives.
struct LaggedContacts {
  int* vertex = nullptr;      // 4 per contact
  double* tangent = nullptr;  // 24 per contact
  double* mu_lambda = nullptr;
  int* environment = nullptr;
  int* contact_begin = nullptr;  // environments + 1 offsets
};

struct FrictionLagStage {
  FrictionLagBuffers b;

  GRIP_HD void operator()(int k) const {
    b.keep[k] = 0;
    if ((b.friction[k] <= 0.0 && !b.at_zero_mu) || b.near_at_rest[k] != 0) return;
    Eigen::Vector3d x[4];
    for (int c = 0; c < 4; ++c) {
      const double* p = b.positions + 3 * b.vertex[4 * k + c];
      x[c] = Eigen::Vector3d(p[0], p[1], p[2]);
    }
    const int e = b.environment[k];
    const bool edge_edge = b.edge_edge[k] != 0;
    const double lambda =
        kernels::contact_normal_force(edge_edge, b.mollifier_eps[k], x, b.d_hat[e], b.kappa[e]);
    if (lambda <= 0.0) return;  // no push, no friction
    const kernels::ContactFrame frame =
        edge_edge ? kernels::edge_edge_frame(x) : kernels::point_triangle_frame(x);
    Eigen::Map<Eigen::Matrix<double, 12, 2>>(b.tangent + 24 * k) = frame.tangent_operator();
    b.mu_lambda[k] = b.friction[k] * lambda;
    b.keep[k] = 1;
  }
};

// The count past the last candidate: 0, so that the scan's last entry is the total.
struct KeepTotalStage {
  FrictionLagBuffers b;
  GRIP_HD void operator()(int) const { b.keep[b.count] = 0; }
};

struct LaggedContactWriteStage {
  FrictionLagBuffers b;
  LaggedContacts out;

  GRIP_HD void operator()(int k) const {
    const int at = b.keep[k];
    if (b.keep[k + 1] == at) return;  // not kept
    for (int c = 0; c < 4; ++c) out.vertex[4 * at + c] = b.vertex[4 * k + c];
    for (int i = 0; i < 24; ++i) out.tangent[24 * at + i] = b.tangent[24 * k + i];
    out.mu_lambda[at] = b.mu_lambda[k];
    out.environment[at] = b.environment[k];
  }
};

// Each environment's first contact (item environment_count: the total).
struct LaggedContactBeginStage {
  FrictionLagBuffers b;
  LaggedContacts out;
  GRIP_HD void operator()(int e) const { out.contact_begin[e] = b.keep[b.candidate_begin[e]]; }
};

// The first half of a lag: each candidate judged, the flags scanned; returns how many contacts
// there are, so that the caller can size `LaggedContacts`.
template <class Launcher>
int count_lagged_contacts(Launcher& launch, const FrictionLagBuffers& b) {
  launch(b.count, FrictionLagStage{b});
  launch(1, KeepTotalStage{b});
  launch.exclusive_scan(b.keep, b.count + 1);
  return launch.fetch(b.keep + b.count);
}

// The second half: the contacts written in the candidates' order.
template <class Launcher>
void write_lagged_contacts(Launcher& launch, const FrictionLagBuffers& b,
                           const LaggedContacts& out) {
  launch(b.count, LaggedContactWriteStage{b, out});
  launch(b.environment_count + 1, LaggedContactBeginStage{b, out});
}

}  // namespace grip::solver::parallel
