#pragma once
// The affine bodies (ABD) of a whole batch of environments in flat arrays, as the data-parallel
// engine's affine stages read them (affine_stages.hpp): per body its first DOF in the batch (12
// DOFs: p, then the rows of A), its environment, its 12x12 mass matrix and inverse, its weight
// factor, volume and orthogonality stiffness, and its drive's stiffness. Driven bodies (a hand's
// links) are affine bodies too: gravity does not act on them, a drive pulls them. Host-built
// from plain values (no Model), so that the device check builds it too; each environment's DOFs
// after the previous one's, as FemBatch lays them.
#include <vector>

namespace grip::solver::parallel {

// What a stage reads of the affine bodies: raw pointers into host or device memory.
struct AffineBuffers {
  int count = 0;
  const int* dof = nullptr;                     // per body: its first DOF in the batch
  const int* environment = nullptr;             // per body
  const double* mass_matrix = nullptr;          // 144 per body, column-major
  const double* mass_matrix_inverse = nullptr;  // 144 per body, column-major
  const double* weight_mass = nullptr;  // per body: density x volume; 0 where gravity does not act
  const double* volume = nullptr;       // per body
  const double* orthogonality_stiffness = nullptr;  // per body, Pa
  const double* drive_stiffness = nullptr;          // per body, N/m; 0: not driven
};

// One affine body as the batch takes it (the CPU engine's AffineBodies and DrivenBodies hold
// the same values).
struct AffineBodyValues {
  const double* mass_matrix = nullptr;          // 144, column-major
  const double* mass_matrix_inverse = nullptr;  // 144, column-major
  double density = 0.0;
  double volume = 0.0;
  double orthogonality_stiffness = 0.0;
  bool falls = true;             // whether gravity acts on it (not on a driven body)
  double drive_stiffness = 0.0;  // N/m; 0: not driven
};

class AffineBatch {
 public:
  // Starts the next environment; its DOFs follow the previous one's.
  void begin_environment(int dof_count);
  // Adds an affine body of the environment begun last, its 12 DOFs from `first_dof` within the
  // environment. Throws std::invalid_argument for a body without mass, volume or stiffness.
  void add_body(int first_dof, const AffineBodyValues& body);

  int environment_count() const { return static_cast<int>(dof_begin_.size()) - 1; }
  int dof_count() const { return dof_begin_.back(); }
  // environment_count() + 1 offsets into the batch's DOFs and its affine bodies.
  const std::vector<int>& dof_begin() const { return dof_begin_; }
  const std::vector<int>& body_begin() const { return body_begin_; }

  AffineBuffers bodies() const;

  // The arrays themselves, for copying to a device.
  const std::vector<int>& dof() const { return dof_; }
  const std::vector<int>& environment() const { return environment_; }
  const std::vector<double>& mass_matrix() const { return mass_matrix_; }
  const std::vector<double>& mass_matrix_inverse() const { return mass_matrix_inverse_; }
  const std::vector<double>& weight_mass() const { return weight_mass_; }
  const std::vector<double>& volume() const { return volume_; }
  const std::vector<double>& orthogonality_stiffness() const { return orthogonality_stiffness_; }
  const std::vector<double>& drive_stiffness() const { return drive_stiffness_; }

 private:
  std::vector<int> dof_begin_{0};
  std::vector<int> body_begin_{0};
  std::vector<int> dof_;
  std::vector<int> environment_;
  std::vector<double> mass_matrix_;
  std::vector<double> mass_matrix_inverse_;
  std::vector<double> weight_mass_;
  std::vector<double> volume_;
  std::vector<double> orthogonality_stiffness_;
  std::vector<double> drive_stiffness_;
};

}  // namespace grip::solver::parallel
