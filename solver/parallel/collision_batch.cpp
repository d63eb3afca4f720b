#include "solver/parallel/collision_batch.hpp"

#include <stdexcept>

namespace grip::solver::parallel {

void CollisionBatch::begin_environment(int dof_count) {
  dof_begin_.push_back(dof_begin_.back() + dof_count);
  vertex_begin_.push_back(vertex_begin_.back());
}

void CollisionBatch::add(VertexMotion motion, int dof, int block_size, double x, double y,
                         double z) {
  if (environment_count() == 0) {
    throw std::logic_error("CollisionBatch: a vertex before begin_environment");
  }
  const int environment = environment_count() - 1;
  int block = -1;
  if (motion != VertexMotion::kScripted) {
    dof += dof_begin_[static_cast<std::size_t>(environment)];
    if (dof < dof_begin_[static_cast<std::size_t>(environment)] ||
        dof + block_size > dof_begin_.back()) {
      throw std::invalid_argument("CollisionBatch: a vertex's DOFs lie outside its environment");
    }
    // An affine body's vertices share its block: the environment's last block of that DOF.
    const bool shared = motion == VertexMotion::kAffine && !block_dof_.empty() &&
                        block_dof_.back() == dof && block_size_.back() == 12;
    if (!shared) {
      block_dof_.push_back(dof);
      block_size_.push_back(block_size);
    }
    block = block_count() - 1;
  }
  motion_.push_back(static_cast<unsigned char>(motion));
  dof_.push_back(motion == VertexMotion::kScripted ? -1 : dof);
  rest_.insert(rest_.end(), {x, y, z});
  environment_.push_back(environment);
  block_.push_back(block);
  vertex_begin_.back() = vertex_count();
}

void CollisionBatch::add_fem_vertex(int first_dof) {
  add(VertexMotion::kFem, first_dof, 3, 0.0, 0.0, 0.0);
}

void CollisionBatch::add_affine_vertex(int body_first_dof, double x, double y, double z) {
  add(VertexMotion::kAffine, body_first_dof, 12, x, y, z);
}

void CollisionBatch::add_scripted_vertex() { add(VertexMotion::kScripted, -1, 0, 0.0, 0.0, 0.0); }

CollisionVertexBuffers CollisionBatch::vertices() const {
  return {vertex_count(), motion_.data(), dof_.data(), rest_.data(), environment_.data()};
}

ContactIncidence contact_incidence(const CollisionBatch& batch, const int* pair_vertex,
                                   int pair_count) {
  // A counting sort of the slots by block: slots stay in increasing order within a block.
  ContactIncidence incidence;
  incidence.begin.assign(static_cast<std::size_t>(batch.block_count()) + 1, 0);
  const std::vector<int>& block = batch.block();
  for (int s = 0; s < 4 * pair_count; ++s) {
    const int b = block[static_cast<std::size_t>(pair_vertex[s])];
    if (b >= 0) ++incidence.begin[static_cast<std::size_t>(b) + 1];
  }
  for (std::size_t b = 1; b < incidence.begin.size(); ++b) {
    incidence.begin[b] += incidence.begin[b - 1];
  }
  incidence.slots.resize(static_cast<std::size_t>(incidence.begin.back()));
  std::vector<int> next(incidence.begin.begin(), incidence.begin.end() - 1);
  for (int s = 0; s < 4 * pair_count; ++s) {
    const int b = block[static_cast<std::size_t>(pair_vertex[s])];
    if (b >= 0) incidence.slots[static_cast<std::size_t>(next[static_cast<std::size_t>(b)]++)] = s;
  }
  return incidence;
}

ContactIncidenceBuffers incidence_buffers(const CollisionBatch& batch,
                                          const ContactIncidence& incidence) {
  return {batch.block_count(), batch.block_dof().data(), batch.block_size().data(),
          incidence.begin.data(), incidence.slots.data()};
}

}  // namespace grip::solver::parallel
