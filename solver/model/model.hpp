#pragma once
// The static part of a scene: everything that never changes during a simulation (the bodies'
// kinds and rest data, the DOF layout, the collision mesh, which pairs may touch). Built once,
// shared read-only by every environment that simulates the same scene.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "solver/body/body_registry.hpp"
#include "solver/body/body_subsystem.hpp"
#include "solver/contact/collision_mesh.hpp"
#include "solver/scene/scene.hpp"

namespace grip::solver {

// One body of the model: the kind that owns its data, and its place in the DOF layout.
struct BodyModel {
  std::string name;
  Material material;
  int dof_offset = 0;  // first DOF in the environment's vector: the bodies' DOFs in body order
  int dof_count = 0;
  const BodySubsystem* kind = nullptr;
  int local = 0;  // its index among the bodies of its kind: what `kind` is asked about

  // In the problem's words (BodySubsystem).
  bool has_dofs() const { return kind->has_dofs(); }
  bool deforms() const { return kind->deforms(); }
  bool scripted() const { return kind->scripted(); }
};

struct PinnedVertex {
  int body = -1;    // the deforming body
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
  // True for DOFs of pinned vertices: prescribed, not solved for.
  const std::vector<char>& prescribed() const { return prescribed_; }

  // mu of the pair, or a negative value when the two bodies never touch (CollisionMesh).
  double pair_friction(int body_a, int body_b) const {
    return collision_.pair_friction(body_a, body_b);
  }
  bool may_touch(int body_a, int body_b) const { return collision_.may_touch(body_a, body_b); }
  bool among_untouching(int body) const { return collision_.among_untouching(body); }

  // The initial description, for initial poses, velocities and scripts.
  const SceneDescription& scene() const { return scene_; }

  // The smallest det F over the tets of every body at DOFs q (1 without tets).
  double min_volume_ratio(const Eigen::VectorXd& q) const;

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
  void build_collision_mesh();
  void build_pair_friction();
  void build_untouching();
  void build_pins();
  void build_rest_proximity();

  SceneDescription scene_;
  SimParameters sim_;
  BodyRegistry kinds_;  // the subsystems that own the bodies' data
  std::vector<BodyModel> bodies_;
  CollisionMesh collision_;
  std::vector<PinnedVertex> pins_;
  std::vector<char> prescribed_;
  std::shared_ptr<const std::vector<int>> ordering_;
  int dof_count_ = 0;
};

}  // namespace grip::solver
