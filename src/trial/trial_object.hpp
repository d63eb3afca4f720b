#pragma once
// The object of a grasp trial: its closed surface in the object frame, a tet mesh when it is
// soft (simulated as FEM, with stress) and its material. Without tets it is one affine body.
#include <optional>
#include <string>

#include "solver/scene/scene.hpp"
#include "src/geometry/mesh.hpp"

namespace grip::trial {

struct TrialObject {
  std::string name;
  geometry::SurfaceMesh surface;          // closed, outward; the rigid body's collision mesh
  std::optional<geometry::TetMesh> tets;  // soft: FEM body (its boundary replaces `surface`)
  solver::Material material;              // density, friction; youngs and poisson if soft

  bool soft() const { return tets.has_value(); }
};

}  // namespace grip::trial
