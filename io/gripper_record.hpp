#pragma once
// One gripper setting of a dataset: what a candidate's pose, joints and closing forces mean
// and the surface whose vertex order per-frame gripper positions follow. A bimanual setting
// is its own gripper record with hands = 2.
#include <cstdint>
#include <string>
#include <vector>

namespace grip::io {

struct GripperRecord {
  std::string name;  // as the job names it: "fin-ray", "leap", "leap-bimanual"
  std::string kind;  // "parallel" or "hand"
  bool soft = false;
  std::uint32_t hands = 1;                // 1, or 2 for bimanual
  std::vector<std::string> joint_names;   // per hand; m for prismatic, rad for revolute
  std::vector<std::string> finger_names;  // per hand; closing forces follow this order
  // 3 per vertex, m: every hand's surface at rest in its own hand frame, hand after hand, as
  // many vertices each (a left hand mirrors the right: the same names, another surface).
  std::vector<double> vertices;
  std::vector<std::int32_t> triangles;  // 3 per triangle, into all hands' vertices
  // A soft gripper's fingers as the solver meshes them, where they lie in `vertices`: 3 per
  // vertex, m, and 4 per tet into them, hand after hand, finger after finger in finger_names'
  // order. Empty for rigid fingers. Finger stress follows this tet order.
  std::vector<double> tet_vertices;
  std::vector<std::int32_t> tets;

  std::size_t vertex_count() const { return vertices.size() / 3; }  // of all hands
};

}  // namespace grip::io
