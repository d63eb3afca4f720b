#include "solver/contact/primitive_trees.hpp"

namespace grip::solver {

void PrimitiveTrees::update(const Model& model, std::span<const Aabb> boxes,
                            const std::vector<int>& first_vertex) {
  boxes_.assign(boxes.begin(), boxes.end());
  all_.build(boxes_);
  const CollisionMesh& mesh = model.collision();
  free_index_.clear();
  free_boxes_.clear();
  free_bounds_ = Aabb{};
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    if (model.among_untouching(mesh.vertex_body[first_vertex[i]])) continue;
    free_index_.push_back(static_cast<int>(i));
    free_boxes_.push_back(boxes_[i]);
    free_bounds_.expand(boxes_[i]);
  }
  free_.build(free_boxes_);
}

}  // namespace grip::solver
