#include "solver/parallel/derivative_stages.hpp"

namespace grip::solver::parallel {

DerivativeStructure derivative_structure(const FemBatch& fem, const AffineBatch& affine,
                                         const CollisionBatch& collision, const ContactPairs& pairs,
                                         const FrictionContacts& friction) {
  DerivativeStructure s;
  s.contact_vertex = pairs.vertex();
  s.contact_vertex.insert(s.contact_vertex.end(), friction.vertex().begin(),
                          friction.vertex().end());
  const int contacts = static_cast<int>(s.contact_vertex.size() / 4);
  s.incidence = contact_incidence(collision, s.contact_vertex.data(), contacts);
  add_tet_stencils(fem, s.slots);
  add_affine_stencils(affine, s.slots);
  add_contact_stencils(collision, s.contact_vertex.data(), contacts, s.slots);
  s.pattern = block_pattern(s.slots, collision.dof_begin());
  std::vector<int> units;
  units.reserve(fem.vertex_dof().size());
  for (const int dof : fem.vertex_dof()) units.push_back(dof / 3);
  s.diagonal = s.pattern.diagonal_blocks(units);
  return s;
}

}  // namespace grip::solver::parallel
