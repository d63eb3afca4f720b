#pragma once
// One kind of body as a subsystem (libuipc's shape): it owns the static data of all the bodies
// of its kind as flat arrays, reports their DOF counts and its block size to the model, which
// lays the DOFs out in body order by prefix sums (Model::build), and computes everything that
// depends on the kind: start state, placement, vertex positions and Jacobians, inertia,
// elasticity and damping, drives, gravity. This is the one declaration of what a kind does;
// fem_bodies, affine_bodies, driven_bodies and kinematic_bodies implement it, and
// body_registry says which kind a description's body is. A body is named here by its index `i`
// among its kind's bodies (BodyModel::local). Shared read-only by every environment of a model:
// an environment's DOFs, poses and scripts come in as arguments.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <array>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "solver/scene/scene.hpp"
#include "solver/scene/state.hpp"

namespace grip::solver {

using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Vector12d = Eigen::Matrix<double, 12, 1>;
// d(vertex position) / d(the DOFs of the block it moves with): 3 x block_size().
using VertexJacobian = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 12>;
using Triplets = std::vector<Eigen::Triplet<double>>;

// One step's Rayleigh damping of a body (Material::damping, beta): its DOFs at the step's start,
// its elastic Hessian K there, one 12 x 12 block per tet (damping_stiffness), and the step's
// length h. The damping is the potential beta / (2 h) |x - x_start|_K^2.
struct StepDamping {
  const Eigen::VectorXd& q_start;
  const std::vector<Matrix12d>& stiffness;
  double h = 0.0;
};

class BodySubsystem {
 public:
  explicit BodySubsystem(int block_size) : block_size_(block_size) {}
  virtual ~BodySubsystem() = default;
  BodySubsystem(const BodySubsystem&) = delete;
  BodySubsystem& operator=(const BodySubsystem&) = delete;

  // Building the model. add() validates a body's description (std::invalid_argument naming the
  // body and the problem) and appends its data; `body` is its index in the scene. Returns i.
  int add(const BodyDescription& description, int body);
  int size() const { return static_cast<int>(body_.size()); }
  // DOFs per block of the Newton matrix: 3 (a vertex), 12 (an affine body) or 0 (no DOFs).
  int block_size() const { return block_size_; }
  virtual int dof_count(int i) const = 0;
  // The body's first DOF in an environment's vector, as the model laid them out.
  void set_dof_offset(int i, int offset) { dof_offset_[static_cast<std::size_t>(i)] = offset; }
  int dof_offset(int i) const { return dof_offset_[static_cast<std::size_t>(i)]; }

  // What a body of the kind is, in the problem's words. Without DOFs it is where its script puts
  // it. A body that deforms moves vertex by vertex: it can touch itself and be pinned.
  bool has_dofs() const { return block_size_ > 0; }
  virtual bool deforms() const { return false; }
  // Whose pose its script moves (exactly, or as a drive's target).
  virtual bool scripted() const { return false; }

  // The rest shape: vertices in the kind's rest frame (a deforming body: world coordinates at
  // t = 0; an affine one: about its centre of mass; one without DOFs: its description's frame).
  virtual int vertex_count(int i) const = 0;
  virtual Eigen::Vector3d rest_vertex(int i, int v) const = 0;
  Vertices rest_vertices(int i) const;
  // Masses lumped at the vertices (kg; empty where the mass is not lumped at vertices).
  virtual Eigen::VectorXd vertex_masses(int /*i*/) const { return {}; }
  // The tetrahedra (vertex indices of the body), none for a body that is not a tet mesh.
  virtual std::span<const std::array<int, 4>> tets(int /*i*/) const { return {}; }
  // The body's mass (kg; 0 without DOFs), and its centre of mass in its description's frame (a
  // body without mass: the frame's origin).
  virtual double mass(int /*i*/) const { return 0.0; }
  virtual Eigen::Vector3d center_of_mass_offset(int /*i*/) const { return Eigen::Vector3d::Zero(); }
  // Calls couple(a, b) for each pair of the body's blocks an element couples, in element order.
  virtual void couple_blocks(int /*i*/, const std::function<void(int, int)>& /*couple*/) const {}

  // An environment's state of the body. initial_state() sets its DOFs and velocities (the pose,
  // script and frame velocity of every body are set by the caller).
  virtual void initial_state(int /*i*/, const BodyDescription& /*description*/,
                             State& /*state*/) const {}
  // Moves the body rigidly by `motion` (velocities turn with it; a driven body's target too).
  virtual void place(int i, const Eigen::Isometry3d& motion, State& state) const = 0;
  // The DOFs a fixture holds the body by (Environment::hold).
  virtual std::vector<int> held_dofs(int /*i*/, const State& /*state*/) const { return {}; }
  virtual Eigen::Vector3d center_of_mass(int i, const State& state) const = 0;
  virtual Eigen::Vector3d center_of_mass_velocity(int i, const State& state) const = 0;
  virtual Eigen::Matrix3d rotation(int i, const State& state) const = 0;

  // World positions at DOFs q (a body without DOFs: at `pose`) of the body's vertices
  // `vertices`, into consecutive rows of `out` from `first_row`.
  virtual void vertex_positions(int i, const Eigen::VectorXd& q, const Pose& pose,
                                std::span<const int> vertices, Vertices& out,
                                Eigen::Index first_row) const = 0;
  // The first DOF of the block vertex v moves with (-1 without DOFs), and its Jacobian there.
  virtual int vertex_block(int /*i*/, int /*v*/) const { return -1; }
  virtual VertexJacobian vertex_jacobian(int /*i*/, int /*v*/) const {
    return VertexJacobian(3, 0);
  }
  // The largest displacement of the body's vertices under the DOF change dq.
  virtual double max_displacement(int /*i*/, const Eigen::VectorXd& /*dq*/) const { return 0.0; }
  // The smallest det F over the body's tets at q (1 without tets).
  virtual double min_volume_ratio(int /*i*/, const Eigen::VectorXd& /*q*/) const { return 1.0; }

  // The body's terms of the incremental potential. Energies are added to `sum`; `scale` times
  // their gradient and (PSD) Hessian are added to `gradient` and the lower-triangle `hessian`
  // triplets (a null `hessian`: the gradient alone). Nothing where the kind has no such term.
  // Gravity: h^2 M^-1 f_gravity added to the inertia target q_tilde.
  virtual void add_gravity(int /*i*/, const Eigen::Vector3d& /*gravity*/, double /*h*/,
                           Eigen::VectorXd& /*q_tilde*/) const {}
  // Inertia: 1/2 |q - q_tilde|_M^2.
  virtual void add_inertia_energy(int /*i*/, const Eigen::VectorXd& /*q*/,
                                  const Eigen::VectorXd& /*q_tilde*/, double& /*sum*/) const {}
  virtual void add_inertia_derivatives(int /*i*/, const Eigen::VectorXd& /*q*/,
                                       const Eigen::VectorXd& /*q_tilde*/, double /*scale*/,
                                       Eigen::VectorXd& /*gradient*/, Triplets* /*hessian*/) const {
  }
  // Elasticity (stable Neo-Hookean; an affine body's orthogonality energy). With `damping`, the
  // derivatives of the Rayleigh damping are summed with the elastic ones element by element.
  virtual void add_elastic_energy(int /*i*/, const Eigen::VectorXd& /*q*/, double& /*sum*/) const {}
  virtual void add_elastic_derivatives(int /*i*/, const Eigen::VectorXd& /*q*/, double /*scale*/,
                                       const StepDamping* /*damping*/,
                                       Eigen::VectorXd& /*gradient*/, Triplets* /*hessian*/) const {
  }
  // Rayleigh damping: whether the body damps, K per tet at q (PSD-projected), and the damping's
  // energy for the step `damping` describes.
  virtual bool damps(int /*i*/) const { return false; }
  virtual void damping_stiffness(int /*i*/, const Eigen::VectorXd& /*q*/,
                                 std::vector<Matrix12d>& /*stiffness*/) const {}
  virtual void add_damping_energy(int /*i*/, const Eigen::VectorXd& /*q*/,
                                  const StepDamping& /*damping*/, double& /*sum*/) const {}
  // A drive: the DOFs its target pose `pose` gives (written into `dofs`), and the energy of the
  // spring towards them, 1/2 (k / m) |q - q_target|_M^2.
  virtual void set_drive_target(int /*i*/, const Pose& /*pose*/, Eigen::VectorXd& /*dofs*/) const {}
  virtual void add_drive_energy(int /*i*/, const Eigen::VectorXd& /*q*/,
                                const Eigen::VectorXd& /*target*/, double& /*sum*/) const {}
  virtual void add_drive_derivatives(int /*i*/, const Eigen::VectorXd& /*q*/,
                                     const Eigen::VectorXd& /*target*/, double /*scale*/,
                                     Eigen::VectorXd& /*gradient*/, Triplets* /*hessian*/) const {}

 protected:
  // Validates the description and appends the body's data (add()).
  virtual void build(const BodyDescription& description) = 0;
  // The body's index in the scene: where its pose, script and frame velocity are in a State.
  int body(int i) const { return body_[static_cast<std::size_t>(i)]; }

 private:
  int block_size_;
  std::vector<int> body_;
  std::vector<int> dof_offset_;
};

// Throws std::invalid_argument("body 'NAME': PROBLEM").
[[noreturn]] void invalid_body(const BodyDescription& body, const std::string& problem);

// The rotation nearest a 3 x 3 matrix (polar decomposition, by SVD).
Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& m);

}  // namespace grip::solver
