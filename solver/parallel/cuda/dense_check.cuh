#pragma once
// The device check's dense Cholesky (grip-gpu-check, dense_check.cu): per environment a system
// shaped like a hand's (17 affine bodies, 204 DOFs): each body's 4 units fully coupled, each
// body coupled to the one before through their first units, random entries and a dominant
// diagonal (positive definite), its first 3 DOFs fixed at random values. Every environment's
// solution on the device must equal the host launcher's to round-off, every one solved.
namespace grip::solver::parallel {

struct DenseCheck {
  double device_ms = 0.0, host_ms = 0.0;
  int dofs = 0;             // per environment
  double solution = 0.0;    // the largest relative difference, per environment
  bool all_solved = false;  // every environment factored, on both
};

DenseCheck check_dense_cholesky(int environments, int repeats);

}  // namespace grip::solver::parallel
