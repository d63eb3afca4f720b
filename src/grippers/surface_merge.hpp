#pragma once
// Appending one surface mesh to another through a rigid or mirroring transform, as when
// gathering posed links or fingers into one mesh.
#include <Eigen/Geometry>

#include "src/geometry/mesh.hpp"

namespace grip::grippers {

// Appends `part` mapped by `transform` to `mesh`. A transform with a negative determinant
// (a mirror) reverses the appended triangles' winding, so outward faces stay outward.
void append_transformed(geometry::SurfaceMesh& mesh, const geometry::SurfaceMesh& part,
                        const Eigen::Affine3d& transform);

}  // namespace grip::grippers
