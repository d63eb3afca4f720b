#include "solver/contact/bvh.hpp"

#include <algorithm>
#include <numeric>

namespace grip::solver {

void Bvh::build(std::span<const Aabb> boxes) {
  nodes_.clear();
  order_.resize(boxes.size());
  std::iota(order_.begin(), order_.end(), 0);
  if (boxes.empty()) return;
  nodes_.reserve(2 * boxes.size() / kLeafSize + 2);
  build_node(boxes, 0, static_cast<int>(boxes.size()));
  leaf_boxes_.resize(boxes.size());
  for (std::size_t i = 0; i < order_.size(); ++i) leaf_boxes_[i] = boxes[order_[i]];
}

// Median split along the longest axis of the centres' extent. The depth stays below
// log2(n / kLeafSize) + 1, far inside the query stack of 64.
int Bvh::build_node(std::span<const Aabb> boxes, int first, int count) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Aabb bounds;
  Aabb centers;
  for (int i = first; i < first + count; ++i) {
    bounds.expand(boxes[order_[i]]);
    centers.expand(boxes[order_[i]].center());
  }
  if (count <= kLeafSize) {
    nodes_[index] = Node{bounds, first, count, -1};
    return index;
  }
  int axis = 0;
  (centers.max - centers.min).maxCoeff(&axis);
  const int half = count / 2;
  // Ties broken by index so the tree does not depend on the sort's implementation.
  std::nth_element(order_.begin() + first, order_.begin() + first + half,
                   order_.begin() + first + count, [&](int a, int b) {
                     const double ca = boxes[a].center()[axis];
                     const double cb = boxes[b].center()[axis];
                     return ca < cb || (ca == cb && a < b);
                   });
  const int left = build_node(boxes, first, half);
  const int right = build_node(boxes, first + half, count - half);
  nodes_[index] = Node{bounds, left, 0, right};
  return index;
}

}  // namespace grip::solver
