#pragma once
// A soft body: a tetrahedral mesh whose DOFs are its vertices' world positions (3 each), with
// lumped masses and stable Neo-Hookean elasticity. Everything the solver does that depends on
// a body being FEM: its model, start state, placement, vertex positions, inertia, elasticity.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <vector>

#include "solver/model.hpp"

namespace grip::solver::fem {

// The FEM part of `body` from its description: rest shape (the start shape, in world
// coordinates), tets, lumped masses, elastic parameters. Throws std::invalid_argument.
void build(const BodyDescription& description, BodyModel& body);

// Start positions and velocities (the description's linear and angular velocity about the
// centre of mass) into q and v.
void initial_state(const BodyModel& body, const BodyDescription& description, Eigen::VectorXd& q,
                   Eigen::VectorXd& v);
void place(const BodyModel& body, const Eigen::Isometry3d& motion, Eigen::VectorXd& q,
           Eigen::VectorXd& v);

inline Eigen::Vector3d vertex_position(const BodyModel& body, const Eigen::VectorXd& q,
                                       int vertex) {
  return q.segment<3>(body.dof_offset + 3 * vertex);
}
// The largest displacement of the body's vertices under the DOF change dq.
double max_displacement(const BodyModel& body, const Eigen::VectorXd& dq);

// Adds h^2 g to the inertia target of every vertex.
void add_gravity(const BodyModel& body, const Eigen::Vector3d& gravity, double h,
                 Eigen::VectorXd& q_tilde);

// The lumped-mass-weighted mean of the body's per-vertex 3-vectors (positions or velocities).
Eigen::Vector3d mass_weighted_mean(const BodyModel& body, const Eigen::VectorXd& values);
// The rotation of the best rigid fit of the vertices to the rest shape.
Eigen::Matrix3d rotation(const BodyModel& body, const Eigen::VectorXd& q);
// The smallest det F over the body's tets (1 without tets).
double min_volume_ratio(const BodyModel& body, const Eigen::VectorXd& q);

// 1/2 |x - x_tilde|_M^2 added to `sum`; `scale` times its gradient and (diagonal) Hessian
// added to the gradient and the lower-triangle triplets (a null `hessian`: the gradient alone).
void add_inertia_energy(const BodyModel& body, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& q_tilde, double& sum);
void add_inertia_derivatives(const BodyModel& body, const Eigen::VectorXd& q,
                             const Eigen::VectorXd& q_tilde, double scale,
                             Eigen::VectorXd& gradient,
                             std::vector<Eigen::Triplet<double>>* hessian);
// The elastic energy added to `sum`.
void add_elastic_energy(const BodyModel& body, const Eigen::VectorXd& q, double& sum);

// Rayleigh damping (Material::damping, beta): the viscous force -beta K v, with K the elastic
// Hessian (PSD-projected) at the step's start and v = (x - x_start) / h, as the potential
// beta / (2 h) |x - x_start|_K^2. tet_stiffness() evaluates K per tet at q; the energy is added
// for the step of length h.
void tet_stiffness(const BodyModel& body, const Eigen::VectorXd& q,
                   std::vector<Matrix12d>& stiffness);
void add_damping_energy(const BodyModel& body, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& q_start, const std::vector<Matrix12d>& stiffness,
                        double h, double& sum);

// One step's damping of a body: its start DOFs, K per tet there (tet_stiffness) and the step's
// length h.
struct StepDamping {
  const Eigen::VectorXd& q_start;
  const std::vector<Matrix12d>& stiffness;
  double h = 0.0;
};

// `scale` times the gradient and PSD-projected Hessian of the elastic energy and, with
// `damping`, of the damping potential, added to the gradient and the lower-triangle triplets
// (a null `hessian`: the gradient alone).
// The two are summed per tet before they are scattered, so a damped tet costs one 12x12 block of
// triplets, not two; where q is still the step's start (a step's first Newton iteration) the
// elastic Hessian is K itself and is not evaluated again.
void add_elastic_derivatives(const BodyModel& body, const Eigen::VectorXd& q, double scale,
                             const StepDamping* damping, Eigen::VectorXd& gradient,
                             std::vector<Eigen::Triplet<double>>* hessian);

}  // namespace grip::solver::fem
