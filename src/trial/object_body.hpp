#pragma once
// The object's side of a trial scene, shared by the parallel-gripper and hand scenes: its
// solver body (one affine body, or FEM when soft; always body 0), its pose, the D1/D2
// distances of gripper points from it, and its stress.
#include <array>
#include <memory>

#include <Eigen/Core>

#include "solver/engine/engine.hpp"
#include "solver/model/model.hpp"
#include "src/geometry/mesh.hpp"
#include "src/geometry/signed_distance.hpp"
#include "src/metrics/distance_metrics.hpp"
#include "src/trial/trial_object.hpp"

namespace grip::trial {

class ObjectBody {
 public:
  explicit ObjectBody(const TrialObject& object);
  ~ObjectBody();
  ObjectBody(ObjectBody&&) noexcept;
  ObjectBody& operator=(ObjectBody&&) noexcept;

  bool soft() const { return soft_; }
  // The body to put first in the scene; a soft one damps with Rayleigh beta soft_damping (s,
  // TrialParameters::object_damping).
  solver::BodyDescription description(double soft_damping) const;
  // Once the scene's Model exists: the soft object's rest centre of mass (by its vertex masses).
  void bind(std::shared_ptr<const solver::Model> model);

  // Row-major 3x4 [A | t], world from object frame (A: the affine body's matrix; a soft
  // object's best-fit rotation).
  std::array<double, 12> pose(const solver::EnvironmentHandle& environment) const;
  // D1/D2 of world points against the object now (a soft object's current surface).
  metrics::DistanceMetrics distances(const solver::EnvironmentHandle& environment,
                                     const geometry::Vertices& points) const;
  // Von Mises stress per tet (Pa) of a soft object now; empty when rigid.
  Eigen::VectorXd stress(const solver::EnvironmentHandle& environment) const;
  // A soft object's rest tets; empty when rigid.
  const geometry::TetMesh& rest_tets() const { return rest_tets_; }

 private:
  bool soft_ = false;
  TrialObject object_;
  std::shared_ptr<const solver::Model> model_;
  std::unique_ptr<geometry::SignedDistance> rigid_distance_;  // object frame
  geometry::SurfaceMesh soft_surface_;  // soft: the tets' boundary over its own vertices
  Eigen::VectorXi soft_surface_to_body_;
  geometry::TetMesh rest_tets_;
  Eigen::Vector3d rest_center_ = Eigen::Vector3d::Zero();  // soft: rest centre of mass
};

}  // namespace grip::trial
