#pragma once
// A bounding volume hierarchy over a fixed set of boxes (one per vertex, edge or triangle of
// an environment), rebuilt per Newton iteration from swept boxes and queried for overlapping
// boxes. Deterministic: the same boxes give the same tree and the same query order.
//
// The tree is built lazily: a node is bounded and split only when a query first reaches it,
// and a node's split depends on its boxes and on the order its parent's split left them in
// alone, so a query finds exactly what it would find in the whole tree, in the same order.
// Queries from a small region (one object among a hand's links) touch a small part of it.
#include <span>
#include <vector>

#include "solver/kernels/aabb.hpp"

namespace grip::solver {

class Bvh {
 public:
  // The boxes must stay alive, unchanged, while the tree is queried.
  void build(std::span<const Aabb> boxes);

  // Calls visit(i) for every box i that overlaps `query`, in a deterministic order.
  template <typename Visit>
  void query(const Aabb& query, Visit&& visit);

  bool empty() const { return nodes_.empty(); }

 private:
  static constexpr int kLeafSize = 4;
  // Node i covers order_[first, first + count): a leaf when count <= kLeafSize, else an inner
  // node with children nodes_[i + 1] (the lower half) and nodes_[right]. The shape depends on
  // the box count alone; `box` and the split are this build's once `opened` and `split` hold
  // its generation.
  struct Node {
    Aabb box;
    int first = 0;
    int count = 0;
    int right = -1;
    int axis = 0;  // the longest axis of the centres' extent
    long opened = -1;
    long split = -1;
  };
  // A box's centre along one axis, the key a node splits its boxes by.
  struct Key {
    double center;
    int box;
  };
  int lay_out(int first, int count);
  void open(Node& node);
  void split(Node& node);

  std::span<const Aabb> boxes_;
  long generation_ = 0;
  std::vector<Node> nodes_;
  std::vector<int> order_;  // box indices, grouped by leaf in the opened nodes
  std::vector<Aabb> leaf_boxes_;
  std::vector<Key> keys_;  // scratch of split()
};

template <typename Visit>
void Bvh::query(const Aabb& query, Visit&& visit) {
  if (nodes_.empty()) return;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int index = stack[--top];
    Node& node = nodes_[index];
    if (node.opened != generation_) open(node);
    if (!node.box.overlaps(query)) continue;
    if (node.count <= kLeafSize) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        if (leaf_boxes_[i].overlaps(query)) visit(order_[i]);
      }
    } else {
      if (node.split != generation_) split(node);
      stack[top++] = node.right;
      stack[top++] = index + 1;
    }
  }
}

}  // namespace grip::solver
