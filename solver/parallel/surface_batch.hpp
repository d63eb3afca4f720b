#pragma once
// The collision surfaces of a whole batch of environments, as the data-parallel broad phase
// (broad_phase.hpp) reads them: per collision vertex its body and rest position; each
// environment's edges and faces; per body whether it is among the bodies that never touch each
// other; per environment the friction of each ordered pair of its bodies (negative: the two
// never touch) and its own pairs near at rest. Vertices, edges, faces and bodies are numbered
// across the batch, each environment's after the previous one's, in the order of the CPU
// engine's CollisionMesh (vertices as CollisionBatch numbers them). Host-built from plain
// values (no Model), so that the device check builds it too.
#include <array>
#include <vector>

namespace grip::solver::parallel {

// What a stage reads of the surfaces: raw pointers into host or device memory.
struct SurfaceBuffers {
  int environment_count = 0;
  int vertex_count = 0, edge_count = 0, face_count = 0, body_count = 0;
  const int* body_begin = nullptr;         // environments + 1 offsets
  const int* body_vertex_begin = nullptr;  // bodies + 1 offsets into the vertices
  const int* friction_begin = nullptr;     // environments + 1 offsets into friction
  const double* friction = nullptr;        // per environment, its bodies' n x n table, row-major
  const int* body_environment = nullptr;
  const char* untouching = nullptr;  // per body
  const int* vertex_body = nullptr;  // per vertex, numbered across the batch
  const int* vertex_environment = nullptr;
  const int* vertex_begin = nullptr;  // environments + 1 offsets
  const double* rest = nullptr;       // 3 per vertex, in its body's rest frame
  const int* edge = nullptr;          // 2 vertices per edge
  const int* edge_environment = nullptr;
  const int* face = nullptr;  // 3 vertices per face
  const int* face_environment = nullptr;
  // Per environment its own pairs near at rest, in its own vertex numbering, sorted: 4 vertices
  // each, environments + 1 offsets (in pairs) each.
  const int* point_triangle_rest_begin = nullptr;
  const int* point_triangle_rest = nullptr;
  const int* edge_edge_rest_begin = nullptr;
  const int* edge_edge_rest = nullptr;
};

class SurfaceBatch {
 public:
  // Starts the next environment: `friction` is its bodies' table (CollisionMesh::friction),
  // `untouching` its bodies' flags.
  void begin_environment(const std::vector<double>& friction, const std::vector<char>& untouching);
  // The next collision vertex of the environment begun last: its body within the environment
  // and its rest position. A body's vertices come one after another, the bodies in order.
  void add_vertex(int body, double x, double y, double z);
  // An edge or face of the environment begun last, by its vertices within the environment.
  void add_edge(int a, int b);
  void add_face(int a, int b, int c);
  // The environment's own pairs near at rest (CollisionMesh), sorted, in its own numbering.
  void set_near_at_rest(const std::vector<std::array<int, 4>>& point_triangle,
                        const std::vector<std::array<int, 4>>& edge_edge);

  int environment_count() const { return static_cast<int>(body_begin_.size()) - 1; }
  const std::vector<int>& vertex_begin() const { return vertex_begin_; }
  SurfaceBuffers buffers() const;

  // The arrays themselves, for copying to a device.
  const std::vector<int>& body_begin() const { return body_begin_; }
  const std::vector<int>& body_vertex_begin() const { return body_vertex_begin_; }
  const std::vector<int>& friction_begin() const { return friction_begin_; }
  const std::vector<double>& friction() const { return friction_; }
  const std::vector<int>& body_environment() const { return body_environment_; }
  const std::vector<char>& untouching() const { return untouching_; }
  const std::vector<int>& vertex_body() const { return vertex_body_; }
  const std::vector<int>& vertex_environment() const { return vertex_environment_; }
  const std::vector<double>& rest() const { return rest_; }
  const std::vector<int>& edge() const { return edge_; }
  const std::vector<int>& edge_environment() const { return edge_environment_; }
  const std::vector<int>& face() const { return face_; }
  const std::vector<int>& face_environment() const { return face_environment_; }
  const std::vector<int>& point_triangle_rest_begin() const { return point_triangle_rest_begin_; }
  const std::vector<int>& point_triangle_rest() const { return point_triangle_rest_; }
  const std::vector<int>& edge_edge_rest_begin() const { return edge_edge_rest_begin_; }
  const std::vector<int>& edge_edge_rest() const { return edge_edge_rest_; }

 private:
  int current() const;  // the environment begun last; throws before the first
  // An environment-local vertex index as the batch's; throws when it is not the environment's.
  int vertex(int local) const;

  std::vector<int> body_begin_{0}, friction_begin_{0}, vertex_begin_{0}, body_vertex_begin_{0};
  std::vector<double> friction_;
  std::vector<int> body_environment_;
  std::vector<char> untouching_;
  std::vector<int> vertex_body_, vertex_environment_;
  std::vector<double> rest_;
  std::vector<int> edge_, edge_environment_, face_, face_environment_;
  std::vector<int> point_triangle_rest_begin_{0}, point_triangle_rest_;
  std::vector<int> edge_edge_rest_begin_{0}, edge_edge_rest_;
};

}  // namespace grip::solver::parallel
