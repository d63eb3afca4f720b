#pragma once
// The static part of a scene: everything that never changes during a simulation (rest shapes,
// masses, DOF layout, the collision mesh, which pairs may touch). Built once, shared read-only
// by every environment that simulates the same scene.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "solver/kernels/neo_hookean.hpp"
#include "solver/scene.hpp"

namespace grip::solver {

using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Vector12d = Eigen::Matrix<double, 12, 1>;

struct FemTet {
  std::array<int, 4> vertices;  // body-local vertex indices
  Eigen::Matrix3d rest_shape_inverse;
  double rest_volume = 0.0;
};

struct BodyModel {
  std::string name;
  BodyType type = BodyType::kAffine;
  int dof_offset = 0;  // first DOF in the environment's vector (FEM: 3 per vertex; affine: 12)
  int dof_count = 0;
  // Rest vertices: FEM in world coordinates at t = 0 (rest = initial shape); affine in a frame
  // at the centre of mass (so the mass matrix has no translation-rotation coupling);
  // kinematic in the body frame of the description.
  Vertices rest;
  Material material;

  // FEM
  std::vector<FemTet> tets;
  Eigen::VectorXd vertex_mass;  // lumped
  kernels::StableNeoHookeanParameters elasticity{0.0, 0.0};

  // affine
  Matrix12d mass_matrix = Matrix12d::Zero();
  Matrix12d mass_matrix_inverse = Matrix12d::Zero();
  Eigen::Vector3d center_of_mass_offset = Eigen::Vector3d::Zero();  // in the description's frame
  double volume = 0.0;
  double orthogonality_stiffness = 0.0;
  double drive_stiffness = 0.0;  // N/m; > 0: driven towards its script's pose
};

// The surface all contacts are found on: vertices of every body, and their edges and faces.
struct CollisionMesh {
  std::vector<int> vertex_body;           // body of each collision vertex
  std::vector<int> vertex_local;          // its index among the body's rest vertices
  std::vector<std::array<int, 2>> edges;  // collision vertex indices
  std::vector<std::array<int, 3>> faces;
  // An FEM body's own point-triangle and edge-edge pairs that lie within d_hat of each other
  // at rest (fine surface triangles at a rim, say), as find_contact_candidates lists them,
  // sorted. No barrier acts on them: it would push the surface apart at rest, against its own
  // elasticity, from the first step. CCD still keeps them from crossing.
  std::vector<std::array<int, 4>> point_triangle_near_at_rest;
  std::vector<std::array<int, 4>> edge_edge_near_at_rest;
  int size() const { return static_cast<int>(vertex_body.size()); }
  bool near_at_rest(bool edge_edge, const std::array<int, 4>& pair) const;
};

struct PinnedVertex {
  int body = -1;    // the FEM body
  int vertex = -1;  // its local vertex
  int kinematic_body = -1;
  Eigen::Vector3d offset;  // the vertex in the kinematic body's frame
};

class Model {
 public:
  // Validates the description (throws std::invalid_argument naming the body and the problem).
  static std::shared_ptr<const Model> build(const SceneDescription& scene);

  const SimParameters& sim() const { return sim_; }
  const std::vector<BodyModel>& bodies() const { return bodies_; }
  const CollisionMesh& collision() const { return collision_; }
  const std::vector<PinnedVertex>& pins() const { return pins_; }
  int dof_count() const { return dof_count_; }
  // True for DOFs of pinned FEM vertices: prescribed, not solved for.
  const std::vector<char>& prescribed() const { return prescribed_; }

  // mu of the pair, or a negative value when the two bodies never touch (both kinematic, a
  // non-FEM body with itself, or a pinned body and its mount).
  double pair_friction(int body_a, int body_b) const {
    return pair_friction_[static_cast<std::size_t>(body_a) * bodies_.size() + body_b];
  }
  bool may_touch(int body_a, int body_b) const { return pair_friction(body_a, body_b) >= 0.0; }
  // Whether the body is one of a set of bodies that never touch each other: the kinematic
  // bodies, with the bodies of collision groups when no pair of the set may touch (a hand's
  // driven links and its palm). The broad phase looks for their contacts only among the
  // others' primitives.
  bool among_untouching(int body) const { return untouching_[static_cast<std::size_t>(body)]; }

  // The initial description, for initial poses, velocities and scripts.
  const SceneDescription& scene() const { return scene_; }

  // A fill-reducing ordering of the Newton matrix's contact-free pattern (inertia, elasticity,
  // pins), computed once and shared by every environment's factorizations: contacts add
  // couplings, but re-ordering for each new contact set costs more than the extra fill.
  const std::shared_ptr<const std::vector<int>>& ordering() const { return ordering_; }
  // The numeric values of CHOLMOD's factor of that pattern under ordering(), bytes, from its
  // symbolic analysis alone: the least one environment's Cholesky needs (contacts add fill), so
  // a farm can tell a model too big for one rank's memory before any numeric work. Computed
  // on each call (about as costly as one symbolic analysis).
  std::size_t contact_free_factor_bytes() const;

 private:
  // The steps of build(), in order.
  void build_bodies();
  void build_pair_friction();
  void build_untouching();
  void build_pins();
  void build_collision_mesh();
  void build_rest_proximity();

  SceneDescription scene_;
  SimParameters sim_;
  std::vector<BodyModel> bodies_;
  CollisionMesh collision_;
  std::vector<PinnedVertex> pins_;
  std::vector<char> prescribed_;
  std::vector<double> pair_friction_;
  std::vector<char> untouching_;
  std::shared_ptr<const std::vector<int>> ordering_;
  int dof_count_ = 0;
};

}  // namespace grip::solver
