#include "solver/contact/primitive_trees.hpp"

namespace grip::solver {

void PrimitiveTrees::update(const CollisionMesh& mesh, std::span<const Aabb> boxes,
                            const std::vector<int>& first_vertex) {
  boxes_.assign(boxes.begin(), boxes.end());
  trees_.resize(static_cast<std::size_t>(mesh.body_count()));
  for (Tree& tree : trees_) {
    tree.index.clear();
    tree.boxes.clear();
    tree.bounds = Aabb{};
  }
  const std::vector<int>& vertex_body = mesh.vertex_body;
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    Tree& tree = trees_[static_cast<std::size_t>(vertex_body[first_vertex[i]])];
    tree.index.push_back(static_cast<int>(i));
    tree.boxes.push_back(boxes_[i]);
    tree.bounds.expand(boxes_[i]);
  }
  for (Tree& tree : trees_) tree.bvh.build(tree.boxes);
}

}  // namespace grip::solver
