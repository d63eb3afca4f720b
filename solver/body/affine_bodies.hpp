#pragma once
// The stiff bodies of affine body dynamics (ABD): 12 DOFs each (its affine matrix A and the
// position p of its centre of mass), rest vertices in a frame at the centre of mass, a full
// 12 x 12 mass matrix and an orthogonality energy that keeps A near a rotation. Body i's rest
// vertices lie at [vertex_begin_[i], vertex_begin_[i + 1]) of one flat array.
#include <Eigen/Core>
#include <vector>

#include "solver/body/body_subsystem.hpp"

namespace grip::solver {

class AffineBodies : public BodySubsystem {
 public:
  AffineBodies() : BodySubsystem(12) {}

  int dof_count(int /*i*/) const override { return 12; }
  int vertex_count(int i) const override { return vertex_begin_[i + 1] - vertex_begin_[i]; }
  Eigen::Vector3d rest_vertex(int i, int v) const override { return rest_[vertex_begin_[i] + v]; }
  double mass(int i) const override { return mass_matrix_[static_cast<std::size_t>(i)](0, 0); }
  Eigen::Vector3d center_of_mass_offset(int i) const override {
    return center_of_mass_offset_[static_cast<std::size_t>(i)];
  }

  void initial_state(int i, const BodyDescription& description, State& state) const override;
  void place(int i, const Eigen::Isometry3d& motion, State& state) const override;
  std::vector<int> held_dofs(int i, const State& state) const override;
  Eigen::Vector3d center_of_mass(int i, const State& state) const override;
  Eigen::Vector3d center_of_mass_velocity(int i, const State& state) const override;
  Eigen::Matrix3d rotation(int i, const State& state) const override;

  void vertex_positions(int i, const Eigen::VectorXd& q, const Pose& pose,
                        std::span<const int> vertices, Vertices& out,
                        Eigen::Index first_row) const override;
  int vertex_block(int i, int /*v*/) const override { return dof_offset(i); }
  VertexJacobian vertex_jacobian(int i, int v) const override;
  double max_displacement(int i, const Eigen::VectorXd& dq) const override;

  void add_gravity(int i, const Eigen::Vector3d& gravity, double h,
                   Eigen::VectorXd& q_tilde) const override;
  void add_inertia_energy(int i, const Eigen::VectorXd& q, const Eigen::VectorXd& q_tilde,
                          double& sum) const override;
  void add_inertia_derivatives(int i, const Eigen::VectorXd& q, const Eigen::VectorXd& q_tilde,
                               double scale, Eigen::VectorXd& gradient,
                               Triplets* hessian) const override;
  // ABD's stiff elasticity; its Hessian PSD-projected. An affine body does not damp.
  void add_elastic_energy(int i, const Eigen::VectorXd& q, double& sum) const override;
  void add_elastic_derivatives(int i, const Eigen::VectorXd& q, double scale,
                               const StepDamping* damping, Eigen::VectorXd& gradient,
                               Triplets* hessian) const override;

  // What the data-parallel engine copies into its flat buffers (parallel/affine_batch.hpp).
  const Matrix12d& mass_matrix(int i) const { return mass_matrix_[static_cast<std::size_t>(i)]; }
  const Matrix12d& mass_matrix_inverse(int i) const {
    return mass_matrix_inverse_[static_cast<std::size_t>(i)];
  }
  double density(int i) const { return density_[static_cast<std::size_t>(i)]; }
  double volume(int i) const { return volume_[static_cast<std::size_t>(i)]; }
  double orthogonality_stiffness(int i) const {
    return orthogonality_stiffness_[static_cast<std::size_t>(i)];
  }

 protected:
  void build(const BodyDescription& description) override;
  // The body's DOFs in `dofs` set to the rigid pose `pose` of its description's frame.
  void set_pose(int i, const Pose& pose, Eigen::VectorXd& dofs) const;
  // 12 x 12 lower-triangle triplets of s M, M the body's mass matrix.
  void add_mass_triplets(int i, double s, Triplets& hessian) const;

 private:
  // Per body.
  std::vector<int> vertex_begin_{0};
  std::vector<Matrix12d> mass_matrix_;
  std::vector<Matrix12d> mass_matrix_inverse_;
  std::vector<Eigen::Vector3d> center_of_mass_offset_;  // in the description's frame
  std::vector<double> volume_;
  std::vector<double> density_;
  std::vector<double> orthogonality_stiffness_;
  // Per vertex: about the centre of mass (so the mass matrix has no translation-rotation
  // coupling).
  std::vector<Eigen::Vector3d> rest_;
};

}  // namespace grip::solver
