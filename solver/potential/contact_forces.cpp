#include "solver/potential/contact_forces.hpp"

#include <algorithm>
#include <map>

#include "solver/contact/candidates.hpp"

namespace grip::solver {

VertexContactForces vertex_contact_forces(const Model& model, const IncrementalPotential& potential,
                                          const Vertices& positions,
                                          const std::vector<ContactCandidate>& near) {
  const CollisionMesh& mesh = model.collision();
  VertexContactForces forces{Vertices::Zero(mesh.size(), 3), Vertices::Zero(mesh.size(), 3)};
  auto add = [](Vertices& to, const std::array<int, 4>& vertex,
                const Eigen::Matrix<double, 12, 1>& f) {
    for (int i = 0; i < 4; ++i) to.row(vertex[i]) += f.segment<3>(3 * i).transpose();
  };
  for (const ContactCandidate& c : near) {
    const ContactForce force = potential.barrier().contact_force(c, positions);
    if (force.magnitude > 0.0) add(forces.normal, c.vertex, force.force);
  }
  for (const FrictionContact& contact : potential.friction().contacts()) {
    add(forces.friction, contact.vertex, potential.friction().force(contact, positions));
  }
  return forces;
}

void PairForceSum::add(const int vertex[4], int side_b, const Eigen::Matrix<double, 12, 1>& f,
                       double normal) {
  const int a = vertex_body_[vertex[0]], b = vertex_body_[vertex[side_b]];
  if (a == b) return;  // self-contact: internal to the body
  const int first = std::min(a, b), second = std::max(a, b);
  PairForce& pf = forces_[{first, second}];
  pf.body_a = first;
  pf.body_b = second;
  pf.normal_force += normal;
  for (int i = 0; i < 4; ++i) {
    if (vertex_body_[vertex[i]] == first) pf.force += f.segment<3>(3 * i);
  }
}

std::vector<PairForce> PairForceSum::pairs() const {
  std::vector<PairForce> result;
  for (const auto& [key, pf] : forces_) result.push_back(pf);
  return result;
}

std::vector<PairForce> pair_forces(const Model& model, const IncrementalPotential& potential,
                                   const Vertices& positions,
                                   const std::vector<ContactCandidate>& near,
                                   double& min_distance) {
  PairForceSum forces(model.collision().vertex_body);
  for (const ContactCandidate& c : near) {
    const ContactForce force = potential.barrier().contact_force(c, positions);
    // Pairs near at rest have no barrier: their distance would drive kappa's adaptation.
    if (!c.near_at_rest && force.distance < model.sim().d_hat) {
      min_distance = std::min(min_distance, force.distance);
    }
    if (force.magnitude > 0.0) {
      forces.add(c.vertex.data(), c.edge_edge ? 2 : 1, force.force, force.magnitude);
    }
  }
  for (const FrictionContact& contact : potential.friction().contacts()) {
    forces.add(contact.vertex.data(), contact.edge_edge ? 2 : 1,
               potential.friction().force(contact, positions), 0.0);
  }
  return forces.pairs();
}

}  // namespace grip::solver
