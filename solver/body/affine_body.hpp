#pragma once
// A stiff body in affine body dynamics (ABD): 12 DOFs (its affine matrix A and the position p
// of its centre of mass), rest vertices in a frame at the centre of mass, a full 12 x 12 mass
// matrix and an orthogonality energy that keeps A near a rotation. Everything the solver does
// that depends on a body being affine.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <vector>

#include "solver/model.hpp"

namespace grip::solver::affine {

// The affine part of `body` from its description: rest vertices about the centre of mass,
// volume, mass matrix, orthogonality stiffness. Throws std::invalid_argument.
void build(const BodyDescription& description, BodyModel& body);

void initial_state(const BodyModel& body, const BodyDescription& description, Eigen::VectorXd& q,
                   Eigen::VectorXd& v);
// The body's DOFs in q set to the rigid pose `pose` of its description's frame.
void set_pose(const BodyModel& body, const Pose& pose, Eigen::VectorXd& q);
void place(const BodyModel& body, const Eigen::Isometry3d& motion, Eigen::VectorXd& q,
           Eigen::VectorXd& v);

Eigen::Vector3d vertex_position(const BodyModel& body, const Eigen::VectorXd& q, int vertex);
// d(vertex position) / d(the body's 12 DOFs).
Eigen::Matrix<double, 3, 12> vertex_jacobian(const BodyModel& body, int vertex);
double max_displacement(const BodyModel& body, const Eigen::VectorXd& dq);

// Adds h^2 M^-1 f_gravity to the body's inertia target; returns its weight |m g| (N).
void add_gravity(const BodyModel& body, const Eigen::Vector3d& gravity, double h,
                 Eigen::VectorXd& q_tilde);

inline Eigen::Vector3d center_of_mass(const BodyModel& body, const Eigen::VectorXd& q) {
  return q.segment<3>(body.dof_offset);
}
// The rotation nearest the body's affine matrix.
Eigen::Matrix3d rotation(const BodyModel& body, const Eigen::VectorXd& q);

// 1/2 (q - q_tilde)^T M (q - q_tilde) added to `sum`; `scale` times its gradient and Hessian
// added (here and below, a null `hessian`: the gradient alone).
void add_inertia_energy(const BodyModel& body, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& q_tilde, double& sum);
void add_inertia_derivatives(const BodyModel& body, const Eigen::VectorXd& q,
                             const Eigen::VectorXd& q_tilde, double scale,
                             Eigen::VectorXd& gradient,
                             std::vector<Eigen::Triplet<double>>* hessian);
// The orthogonality energy (ABD's stiff elasticity) added to `sum`; `scale` times its gradient
// and PSD-projected Hessian added.
void add_elastic_energy(const BodyModel& body, const Eigen::VectorXd& q, double& sum);
void add_elastic_derivatives(const BodyModel& body, const Eigen::VectorXd& q, double scale,
                             Eigen::VectorXd& gradient,
                             std::vector<Eigen::Triplet<double>>* hessian);

}  // namespace grip::solver::affine
