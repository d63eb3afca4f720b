#pragma once
// What the MuJoCo trials of `grip bench peer` share (built with MuJoCo only): a grip surface as
// an MJCF mesh asset, an MJCF string loaded into a model, a body's world pose.
#if GRIP_HAVE_MUJOCO
#include <mujoco/mujoco.h>

#include <ostream>
#include <string>

#include <Eigen/Geometry>

#include "src/geometry/mesh.hpp"

namespace grip::bench {

// <mesh name="NAME" vertex="..." face="..."/>; `x` at full precision.
void write_mesh_asset(std::ostream& x, const std::string& name, const geometry::SurfaceMesh& mesh);

// The model of an MJCF string, through MuJoCo's in-memory file system; null with MuJoCo's
// error in `message` if it does not compile. MuJoCo's warnings are read from mjData::warning.
mjModel* load_model(const std::string& xml, std::string& message);

// World from body frame.
Eigen::Isometry3d body_pose(const mjData* d, int body);

}  // namespace grip::bench
#endif
