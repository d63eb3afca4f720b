#include "solver/contact/bvh.hpp"

#include <algorithm>
#include <numeric>

namespace grip::solver {

void Bvh::build(std::span<const Aabb> boxes) {
  if (boxes.size() != order_.size()) {
    order_.resize(boxes.size());
    nodes_.clear();
    if (!boxes.empty()) lay_out(0, static_cast<int>(boxes.size()));
    leaf_boxes_.resize(boxes.size());
    keys_.resize(boxes.size());
  }
  boxes_ = boxes;
  std::iota(order_.begin(), order_.end(), 0);
  ++generation_;
}

// Median splits: the depth stays below log2(n / kLeafSize) + 1, far inside the query stack of
// 64. Returns the index after the subtree's nodes.
int Bvh::lay_out(int first, int count) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back(Node{Aabb{}, first, count, -1});
  if (count <= kLeafSize) return index + 1;
  const int half = count / 2;
  const int right = lay_out(first, half);
  nodes_[index].right = right;
  return lay_out(first + half, count - half);
}

void Bvh::open(Node& node) {
  Aabb bounds;
  Aabb centers;
  for (int i = node.first; i < node.first + node.count; ++i) {
    const Aabb& box = boxes_[order_[i]];
    bounds.expand(box);
    centers.expand(box.center());
  }
  node.box = bounds;
  if (node.count <= kLeafSize) {
    for (int i = node.first; i < node.first + node.count; ++i) leaf_boxes_[i] = boxes_[order_[i]];
  } else {
    (centers.max - centers.min).maxCoeff(&node.axis);
  }
  node.opened = generation_;
}

// Along the longest axis of the centres' extent, the lower half of the centres to the first
// child.
void Bvh::split(Node& node) {
  const int first = node.first;
  const int count = node.count;
  const int axis = node.axis;
  Key* keys = keys_.data() + first;
  for (int i = 0; i < count; ++i) {
    keys[i] = {boxes_[order_[first + i]].center()[axis], order_[first + i]};
  }
  // Ties broken by index so the split does not depend on the sort's implementation.
  std::nth_element(keys, keys + count / 2, keys + count, [](const Key& a, const Key& b) {
    return a.center < b.center || (a.center == b.center && a.box < b.box);
  });
  for (int i = 0; i < count; ++i) order_[first + i] = keys[i].box;
  node.split = generation_;
}

}  // namespace grip::solver
