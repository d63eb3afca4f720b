#pragma once
// A soft box for scene files: a structured tet grid (exact volume, no meshing needed). The
// other primitive shapes come from src/geometry/primitives.hpp.
#include "src/geometry/mesh.hpp"

namespace grip::scene {

// A box of full extents `size` split into cells of about `cell` (at least one per axis), six
// positively oriented tets per cell (Kuhn's split, conforming across cells).
geometry::TetMesh box_tets(const Eigen::Vector3d& size, double cell);

}  // namespace grip::scene
