#pragma once
// The soft bodies: tetrahedral meshes whose DOFs are their vertices' world positions (3 each),
// with lumped masses, stable Neo-Hookean elasticity and Rayleigh damping. The data of every FEM
// body lies in flat arrays: vertices (rest positions, lumped masses) and tets (vertex indices,
// Dm^-1, rest volumes) of body i at [vertex_begin_[i], vertex_begin_[i + 1]) and
// [tet_begin_[i], tet_begin_[i + 1]).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "solver/body/body_subsystem.hpp"
#include "solver/kernels/neo_hookean.hpp"

namespace grip::solver {

class FemBodies final : public BodySubsystem {
 public:
  FemBodies() : BodySubsystem(3) {}

  int dof_count(int i) const override { return 3 * vertex_count(i); }
  bool deforms() const override { return true; }
  int vertex_count(int i) const override { return vertex_begin_[i + 1] - vertex_begin_[i]; }
  Eigen::Vector3d rest_vertex(int i, int v) const override { return rest_[vertex_begin_[i] + v]; }
  Eigen::VectorXd vertex_masses(int i) const override;
  std::span<const std::array<int, 4>> tets(int i) const override;
  double mass(int i) const override { return mass_[static_cast<std::size_t>(i)]; }
  Eigen::Vector3d center_of_mass_offset(int i) const override;
  void couple_blocks(int i, const std::function<void(int, int)>& couple) const override;

  void initial_state(int i, const BodyDescription& description, State& state) const override;
  void place(int i, const Eigen::Isometry3d& motion, State& state) const override;
  std::vector<int> held_dofs(int i, const State& state) const override;
  Eigen::Vector3d center_of_mass(int i, const State& state) const override;
  Eigen::Vector3d center_of_mass_velocity(int i, const State& state) const override;
  Eigen::Matrix3d rotation(int i, const State& state) const override;

  void vertex_positions(int i, const Eigen::VectorXd& q, const Pose& pose,
                        std::span<const int> vertices, Vertices& out,
                        Eigen::Index first_row) const override;
  int vertex_block(int i, int v) const override { return dof_offset(i) + 3 * v; }
  VertexJacobian vertex_jacobian(int i, int v) const override;
  double max_displacement(int i, const Eigen::VectorXd& dq) const override;
  double min_volume_ratio(int i, const Eigen::VectorXd& q) const override;

  void add_gravity(int i, const Eigen::Vector3d& gravity, double h,
                   Eigen::VectorXd& q_tilde) const override;
  void add_inertia_energy(int i, const Eigen::VectorXd& q, const Eigen::VectorXd& q_tilde,
                          double& sum) const override;
  void add_inertia_derivatives(int i, const Eigen::VectorXd& q, const Eigen::VectorXd& q_tilde,
                               double scale, Eigen::VectorXd& gradient,
                               Triplets* hessian) const override;
  void add_elastic_energy(int i, const Eigen::VectorXd& q, double& sum) const override;
  // The two are summed per tet before they are scattered, so a damped tet costs one 12x12 block
  // of triplets, not two; where q is still the step's start (a step's first Newton iteration)
  // the elastic Hessian is K itself and is not evaluated again.
  void add_elastic_derivatives(int i, const Eigen::VectorXd& q, double scale,
                               const StepDamping* damping, Eigen::VectorXd& gradient,
                               Triplets* hessian) const override;
  bool damps(int i) const override { return damping_[static_cast<std::size_t>(i)] > 0.0; }
  void damping_stiffness(int i, const Eigen::VectorXd& q,
                         std::vector<Matrix12d>& stiffness) const override;
  void add_damping_energy(int i, const Eigen::VectorXd& q, const StepDamping& damping,
                          double& sum) const override;

 private:
  void build(const BodyDescription& description) override;
  // The lumped-mass-weighted mean of the body's per-vertex 3-vectors (positions or velocities).
  Eigen::Vector3d mass_weighted_mean(int i, const Eigen::VectorXd& values) const;

  // Body i's tets in the flat arrays, and its elastic parameters.
  struct TetView {
    int count;
    const std::array<int, 4>* vertices;
    const Eigen::Matrix3d* rest_shape_inverse;
    const double* rest_volume;
    const kernels::StableNeoHookeanParameters& elasticity;
  };
  TetView tet_view(int i) const;

  // Per body.
  std::vector<int> vertex_begin_{0};
  std::vector<int> tet_begin_{0};
  std::vector<double> mass_;  // the sum of its lumped masses
  std::vector<kernels::StableNeoHookeanParameters> elasticity_;
  std::vector<double> damping_;  // Rayleigh beta (s)
  std::vector<Eigen::Vector3d> center_of_mass_offset_;
  // Per vertex.
  std::vector<Eigen::Vector3d> rest_;  // world coordinates at t = 0
  std::vector<double> vertex_mass_;
  // Per tet.
  std::vector<std::array<int, 4>> tet_vertices_;  // vertex indices of its body
  std::vector<Eigen::Matrix3d> rest_shape_inverse_;
  std::vector<double> rest_volume_;
};

}  // namespace grip::solver
