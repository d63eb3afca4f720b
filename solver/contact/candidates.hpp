#pragma once
// The broad phase of one environment: point-triangle and edge-edge pairs of the collision mesh
// whose boxes, swept from one configuration to another and inflated by d_hat, overlap. The
// list holds every pair that can come within d_hat anywhere on the straight path between the
// two configurations, so it serves CCD and every barrier evaluation along that path.
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "solver/contact/collision_mesh.hpp"
#include "solver/contact/primitive_trees.hpp"

namespace grip::solver {

// A broad-phase candidate: two primitives that may come within d_hat.
struct ContactCandidate {
  bool edge_edge = false;      // else point-triangle
  std::array<int, 4> vertex;   // collision vertices: (p, t0, t1, t2) or (ea0, ea1, eb0, eb1)
  double friction = 0.0;       // mu of the two bodies
  double mollifier_eps = 0.0;  // edge-edge: eps_x of the parallel-edge mollifier (rest lengths)
  // One FEM body's primitives within d_hat at rest (CollisionMesh::point_triangle_near_at_rest):
  // CCD watches the pair, no barrier acts on it.
  bool near_at_rest = false;
};

// Pairs near the path start -> end (both collision vertex positions, one row per vertex), in a
// deterministic order: point-triangle pairs by vertex then face, then edge-edge pairs by edge
// then partner edge (indices of the collision mesh). Pairs that share a vertex, and pairs of bodies
// that never touch, are left out.
std::vector<ContactCandidate> find_contact_candidates(const CollisionMesh& mesh,
                                                      const Vertices& start, const Vertices& end,
                                                      double d_hat);

// The candidates of the path start -> end that can come within d_hat on it, in their order
// (vertex_body: each collision vertex's body, CollisionMesh::vertex_body). A
// pair is left out when its distance at the start exceeds d_hat plus its vertices' largest
// displacements (a point's and its triangle's farthest-moving vertex, or each edge's): no point of
// the path brings it within d_hat, so its barrier is zero all along. Most pairs of a finely meshed
// soft finger are neighbours on its surface, a few millimetres apart: their boxes overlap, their
// barrier never acts. A pair of one body keeps its distance under any motion its vertices share,
// so for it the displacements are taken less its body's (displacements_in_body): a finger that
// moves by half a millimetre as a whole brings none of its own pairs nearer.
//
// With `ccd`, also the pairs continuous collision detection must watch, in order: those within
// reach, and those that start farther than d_hat / ccd_rescaling and move fast enough to close
// (1 - ccd_rescaling) of their gap on the path. Additive CCD stops a pair only once its distance
// falls below ccd_rescaling times its start distance; a pair that stays beyond d_hat and starts
// nearer than d_hat / ccd_rescaling never gets there, and one whose relative motion is shorter
// than (1 - ccd_rescaling) of its gap is cleared by CCD's first advance
// (kernels::accd_clears_at_first_advance), so leaving them out leaves the step's collision-free
// fraction as it was. An object falling past a finely meshed hand overlaps tens of thousands of
// such pairs per iteration.
std::vector<ContactCandidate> within_reach(const std::vector<int>& vertex_body,
                                           const std::vector<ContactCandidate>& candidates,
                                           const Vertices& start, const Vertices& end, double d_hat,
                                           std::vector<ContactCandidate>* ccd = nullptr,
                                           double ccd_rescaling = 0.0);

// Each collision vertex's displacement from -> to, less its body's common motion (the centre of
// the box of its body's displacements), as a length. vertex_body: each collision vertex's body
// (CollisionMesh::vertex_body), as within_reach takes it.
Eigen::VectorXd displacements_in_body(const std::vector<int>& vertex_body, const Vertices& from,
                                      const Vertices& to);

// Broad-phase pairs in the candidates' order, with their primitives: (vertex, face) or
// (edge, edge), collision mesh indices, and each pair's place in that order as one number.
struct KeptPairs {
  std::vector<ContactCandidate> pairs;
  std::vector<std::array<int, 2>> primitives;
  std::vector<std::uint64_t> order;  // edge-edge after point-triangle, then by the primitives
  void clear();
  void add(const ContactCandidate& pair, const std::array<int, 2>& primitive_pair);
};

// The broad phase kept from call to call (one per environment); it finds exactly what
// find_contact_candidates finds, in the same order. It keeps the pairs whose boxes overlap once
// every vertex's box is grown by a skin (a Verlet list): while each later call's vertex boxes
// lie inside those grown boxes, that call's pairs are among the kept ones, and it only tests the
// kept pairs' boxes instead of querying the trees. A Newton iteration moves vertices by far less
// than the skin, so the trees are queried about once per step rather than twice per iteration.
//
// Each body's own pairs are kept apart from the pairs of two bodies, and kept again only when it
// deforms past the skin: whether two boxes of one body overlap does not change when the
// body moves as a whole, so their cover is tested with each body's boxes moved back by its
// common motion. A soft finger's own pairs, most of all pairs, are then kept again only while
// it bends, not whenever it or the object moves.
class ContactBroadPhase {
 public:
  std::vector<ContactCandidate> find(const CollisionMesh& mesh, const Vertices& start,
                                     const Vertices& end, double d_hat);

  // within_reach(mesh.vertex_body, find(mesh, start, end, d_hat), start, end, d_hat, ccd,
  // ccd_rescaling), the same pairs in the same order, without testing most pairs of one body.
  // Each such kept pair whose box overlaps is measured where it was kept, once per keep; its
  // vertices have since moved, and move on the path, by at most their displacements in their
  // body, so a pair that distance keeps beyond reach (and, with `ccd`, short of d_hat /
  // ccd_rescaling) is passed over without a distance. Most of a soft finger's kept pairs are the
  // two faces of a wall or rib 1.5-2.5 mm apart, which only deformation, never the finger's
  // motion, can bring within d_hat.
  std::vector<ContactCandidate> near(const CollisionMesh& mesh, const Vertices& start,
                                     const Vertices& end, double d_hat,
                                     std::vector<ContactCandidate>* ccd = nullptr,
                                     double ccd_rescaling = 0.0);

  // How many calls queried the trees for the pairs of two bodies (the others reused the kept
  // pairs), and how many times a body's own pairs were kept again (per body).
  long keeps() const { return keeps_; }
  long one_body_keeps() const { return one_body_keeps_; }
  // How many kept pairs whose boxes overlap near() passed over by their kept distance.
  long screened() const { return screened_; }

 private:
  // The skin, as a multiple of d_hat: each vertex's box is grown by half of it on every side.
  static constexpr double kSkin = 1.0;
  // Each vertex's swept box, and the face and edge boxes; keeps the pairs again when the kept
  // ones no longer cover the call.
  void prepare(const CollisionMesh& mesh, const Vertices& start, const Vertices& end, double d_hat);
  // Whether each body's own pairs cover the call: each of its vertices' boxes, moved back by the
  // body's common motion since they were kept, lies inside its box kept for them. Marks the
  // bodies whose own do not (deformed_).
  bool own_pairs_cover(const CollisionMesh& mesh, const Vertices& start, const Vertices& end,
                       double d_hat);
  // The kept pairs whose boxes overlap now, in order, but those skip(i) passes over (asked only
  // of the overlapping ones).
  template <typename Skip>
  std::vector<ContactCandidate> overlapping(Skip&& skip);
  void keep(const CollisionMesh& mesh, const Vertices& start, double d_hat);
  // kept_ from the pairs of two bodies and each body's own.
  void merge_kept();

  PrimitiveTrees faces_;
  PrimitiveTrees edges_;
  const CollisionMesh* kept_mesh_ = nullptr;
  // Scratch of a keep: the pairs of two bodies, and per body its own (none for a rigid one).
  KeptPairs two_bodies_;
  std::vector<KeptPairs> own_;
  KeptPairs kept_;  // all of them, in order (merge_kept)
  // Whether each is a body's own pair. on_one_body() would say so from the collision mesh, but
  // near() asks for every overlapping pair, and the flags read in order cost less (the fin-ray
  // cylinder's broad phase was 2-3 % slower without them).
  std::vector<char> kept_own_;
  // The kept own pairs' distances at the last keep's start, measured when near() first needs
  // them (kUnmeasured until then); empty until near() is called after a keep.
  std::vector<double> kept_distance_;
  static constexpr double kUnmeasured = -1.0;
  std::vector<Aabb> kept_vertex_boxes_;  // grown boxes of the last keep
  Vertices kept_start_;                  // the start of its call
  std::vector<Aabb> own_vertex_boxes_;   // each vertex's as its body's own pairs were kept
  Vertices own_start_;                   // and its start then
  std::vector<char> deformed_;           // per body: its own pairs are to be kept again
  long keeps_ = 0;
  long one_body_keeps_ = 0;
  long screened_ = 0;
  // Scratch of one call.
  std::vector<Aabb> vertex_boxes_;
  std::vector<Aabb> face_boxes_;
  std::vector<Aabb> edge_boxes_;
  std::vector<Aabb> boxes_;
  std::vector<int> first_vertex_;
  std::vector<int> hits_;
  std::vector<Aabb> body_motion_;
};

// The deforming bodies' own pairs within d_hat at rest, point-triangle then edge-edge, each
// sorted: what the model keeps in the mesh (CollisionMesh::point_triangle_near_at_rest).
std::pair<std::vector<std::array<int, 4>>, std::vector<std::array<int, 4>>> self_pairs_near_at_rest(
    const CollisionMesh& mesh, double d_hat);

}  // namespace grip::solver
