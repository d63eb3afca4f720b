#pragma once
// The one place the solver dispatches on a body's kind (FEM, affine, kinematic): each function
// here forwards to solver/body/fem_body, affine_body or kinematic_body. The rest of the solver
// asks these and never branches on BodyType itself.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "solver/model.hpp"
#include "solver/state.hpp"

namespace grip::solver {

// Throws std::invalid_argument("body 'NAME': PROBLEM").
[[noreturn]] void invalid_body(const BodyDescription& body, const std::string& problem);

// The rotation nearest a 3 x 3 matrix (polar decomposition, by SVD).
Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& m);

inline bool is_kinematic(const BodyModel& body) { return body.type == BodyType::kKinematic; }
// A driven body follows its script's pose through a spring (BodyDescription::drive_stiffness).
inline bool is_driven(const BodyModel& body) { return body.drive_stiffness > 0.0; }
// Whose pose its script moves: a kinematic body's, or a driven body's drive target.
inline bool is_scripted(const BodyModel& body) { return is_kinematic(body) || is_driven(body); }
// Only a soft body can touch itself; a stiff or kinematic one keeps its shape.
inline bool can_self_collide(BodyType type) { return type == BodyType::kFem; }

// The kind's part of a body's model (rest shape, masses, DOF count).
void build_body(const BodyDescription& description, BodyModel& body);

// The body's start state (DOFs and velocities, or pose, script and frame velocity).
void initial_body_state(const BodyModel& body, int index, const BodyDescription& description,
                        State& state);
// Moves the body rigidly by `motion` (velocities turn with it; a driven body's target with it).
void place_body(const BodyModel& body, int index, const Eigen::Isometry3d& motion, State& state);

// A body vertex's world position at DOFs q; kinematic bodies are at `pose`.
Eigen::Vector3d vertex_position(const BodyModel& body, const Eigen::VectorXd& q, const Pose& pose,
                                int vertex);
// DOFs per block of the Newton matrix (3 for an FEM vertex, 12 for an affine body, 0 kinematic).
int block_size(const BodyModel& body);
// The first DOF of the block a body vertex moves with, or -1 for a kinematic body.
int vertex_block(const BodyModel& body, int vertex);
// d(vertex position) / d(the block's DOFs): 3 x block_size(body).
Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 12> vertex_jacobian(const BodyModel& body,
                                                                   int vertex);
// The largest displacement of the body's vertices under the DOF change dq (0 kinematic).
double max_displacement(const BodyModel& body, const Eigen::VectorXd& dq);
// Adds gravity's h^2 M^-1 f to the inertia target.
void add_gravity(const BodyModel& body, const Eigen::Vector3d& gravity, double h,
                 Eigen::VectorXd& q_tilde);
// The body's mass (kg; 0 for a kinematic body).
double body_mass(const BodyModel& body);
// A driven body's drive: the energy 1/2 (k / m) |q - q_target|_M^2 of its spring (k the drive
// stiffness, m the body's mass, M its mass matrix), added to `sum`, and `scale` times its
// derivatives added to the gradient and lower-triangle triplets; `target` the DOFs of the
// script's pose. Nothing for a body that is not driven.
void add_drive_energy(const BodyModel& body, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& target, double& sum);
void add_drive_derivatives(const BodyModel& body, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& target, double scale, Eigen::VectorXd& gradient,
                           std::vector<Eigen::Triplet<double>>* hessian);
// The DOFs a driven body has at `pose` (its script's frame), written into `dofs`.
void set_drive_target(const BodyModel& body, const Pose& pose, Eigen::VectorXd& dofs);

Eigen::Vector3d center_of_mass(const BodyModel& body, int index, const State& state);
Eigen::Vector3d center_of_mass_velocity(const BodyModel& body, int index, const State& state);
Eigen::Matrix3d body_rotation(const BodyModel& body, int index, const State& state);
// The smallest det F over the tets of every FEM body (1 without FEM).
double min_volume_ratio(const Model& model, const Eigen::VectorXd& q);

// Inertia and elasticity of one body (nothing for a kinematic one): energies added to `sum`,
// `scale` times their derivatives added to the gradient and lower-triangle triplets (here and
// below, a null `hessian` asks for the gradient alone).
void add_inertia_energy(const BodyModel& body, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& q_tilde, double& sum);
void add_inertia_derivatives(const BodyModel& body, const Eigen::VectorXd& q,
                             const Eigen::VectorXd& q_tilde, double scale,
                             Eigen::VectorXd& gradient,
                             std::vector<Eigen::Triplet<double>>* hessian);
void add_elastic_energy(const BodyModel& body, const Eigen::VectorXd& q, double& sum);
void add_elastic_derivatives(const BodyModel& body, const Eigen::VectorXd& q, double scale,
                             Eigen::VectorXd& gradient,
                             std::vector<Eigen::Triplet<double>>* hessian);

}  // namespace grip::solver
