#pragma once
// One object of a dataset as written once at plan time: identity, material and the meshes
// whose vertex order every per-frame array of the object follows.
#include <cstdint>
#include <string>
#include <vector>

namespace grip::io {

struct Material {
  double young_modulus = 0;  // Pa
  double poisson_ratio = 0;
  double density = 0;   // kg/m^3
  double friction = 0;  // dry friction coefficient against the gripper
};

struct ObjectRecord {
  std::string name;
  std::string category;
  double scale = 1;   // the randomized scale already applied to `vertices`
  bool soft = false;  // soft: FEM tet body with stress; rigid: one affine body
  Material material;
  std::vector<double> vertices;         // 3 per vertex, m, rest shape in the object frame
  std::vector<std::int32_t> triangles;  // 3 per boundary triangle, zero-based, outward
  std::vector<std::int32_t> tets;       // 4 per tet (soft objects; may be empty when rigid)

  std::size_t vertex_count() const { return vertices.size() / 3; }
  std::size_t tet_count() const { return tets.size() / 4; }
};

}  // namespace grip::io
