#pragma once
// One kind of primitive of a collision mesh (faces or edges) in a tree per body, for the broad
// phase. A primitive looks only in the trees of the bodies it may touch: its own body's for the
// pairs of one body (a soft finger's), the others' for the pairs of two. The pairs of one body
// and of two are kept at different times (ContactBroadPhase), and a query for one kind never
// walks the other's primitives: most of a soft finger's neighbours are its own.
#include <span>
#include <vector>

#include "solver/contact/bvh.hpp"
#include "solver/contact/collision_mesh.hpp"

namespace grip::solver {

class PrimitiveTrees {
 public:
  // boxes[i] and first_vertex[i]: primitive i's swept box and one of its collision vertices.
  // The trees keep their storage from update to update.
  void update(const CollisionMesh& mesh, std::span<const Aabb> boxes,
              const std::vector<int>& first_vertex);

  const Aabb& box(int i) const { return boxes_[static_cast<std::size_t>(i)]; }
  // The union of one body's primitives' boxes.
  const Aabb& bounds(int body) const { return trees_[static_cast<std::size_t>(body)].bounds; }

  // Calls visit(primitive index) for each of `body`'s primitives whose box overlaps `box`.
  template <typename Visit>
  void query(int body, const Aabb& box, Visit&& visit) {
    Tree& tree = trees_[static_cast<std::size_t>(body)];
    if (!tree.bounds.overlaps(box)) return;
    tree.bvh.query(box, [&](int k) { visit(tree.index[static_cast<std::size_t>(k)]); });
  }

 private:
  struct Tree {
    Bvh bvh;
    std::vector<int> index;  // the tree's boxes as primitive indices
    std::vector<Aabb> boxes;
    Aabb bounds;
  };
  std::vector<Aabb> boxes_;
  std::vector<Tree> trees_;
};

}  // namespace grip::solver
