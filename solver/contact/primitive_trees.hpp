#pragma once
// One kind of primitive of a collision mesh (faces or edges) in two trees, for the broad phase.
// Untouching bodies never touch each other (Model::among_untouching: kinematic jaws, a hand's
// links), and they can hold most of the primitives: theirs look only among the other bodies'
// primitives, in a second, smaller tree over those (the free tree).
#include <span>
#include <vector>

#include "solver/contact/bvh.hpp"
#include "solver/model.hpp"

namespace grip::solver {

class PrimitiveTrees {
 public:
  // boxes[i] and first_vertex[i]: primitive i's swept box and one of its collision vertices.
  // The trees keep their storage from update to update.
  void update(const Model& model, std::span<const Aabb> boxes,
              const std::vector<int>& first_vertex);

  const Aabb& box(int i) const { return boxes_[static_cast<std::size_t>(i)]; }
  // The union of the free (not untouching) primitives' boxes.
  const Aabb& free_bounds() const { return free_bounds_; }

  // Calls visit(primitive index) for each box of the right tree that overlaps `box`.
  template <typename Visit>
  void query(bool from_untouching, const Aabb& box, Visit&& visit) {
    if (from_untouching) {
      free_.query(box, [&](int k) { visit(free_index_[static_cast<std::size_t>(k)]); });
    } else {
      all_.query(box, visit);
    }
  }

 private:
  std::vector<Aabb> boxes_;
  Bvh all_;
  Bvh free_;
  std::vector<int> free_index_;  // the free tree's boxes as primitive indices
  std::vector<Aabb> free_boxes_;
  Aabb free_bounds_;
};

}  // namespace grip::solver
