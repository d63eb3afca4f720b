#pragma once
// A bounding volume hierarchy over a fixed set of boxes (one per vertex, edge or triangle of
// an environment), rebuilt per time step from swept boxes and queried for overlapping boxes.
// Deterministic: the same boxes give the same tree and the same query order.
#include <span>
#include <vector>

#include "solver/contact/aabb.hpp"

namespace grip::solver {

class Bvh {
 public:
  void build(std::span<const Aabb> boxes);

  // Calls visit(i) for every box i that overlaps `query`, in a deterministic order.
  template <typename Visit>
  void query(const Aabb& query, Visit&& visit) const;

  bool empty() const { return nodes_.empty(); }

 private:
  static constexpr int kLeafSize = 4;
  // A leaf (count > 0) holds order_[first, first + count); an inner node (count == 0) has
  // children nodes_[first] and nodes_[right].
  struct Node {
    Aabb box;
    int first = 0;
    int count = 0;
    int right = -1;
  };
  int build_node(std::span<const Aabb> boxes, int first, int count);

  std::vector<Node> nodes_;
  std::vector<int> order_;  // box indices, grouped by leaf
  std::vector<Aabb> leaf_boxes_;
};

template <typename Visit>
void Bvh::query(const Aabb& query, Visit&& visit) const {
  if (nodes_.empty()) return;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!node.box.overlaps(query)) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        if (leaf_boxes_[i].overlaps(query)) visit(order_[i]);
      }
    } else {
      stack[top++] = node.right;
      stack[top++] = node.first;
    }
  }
}

}  // namespace grip::solver
