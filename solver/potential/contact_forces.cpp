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

std::vector<PairForce> pair_forces(const Model& model, const IncrementalPotential& potential,
                                   const Vertices& positions,
                                   const std::vector<ContactCandidate>& near,
                                   double& min_distance) {
  const CollisionMesh& mesh = model.collision();
  std::map<std::pair<int, int>, PairForce> forces;
  // Adds the force on a stencil's vertices to the pair (side A's body, side B's body).
  auto add = [&](const std::array<int, 4>& vertex, bool edge_edge,
                 const Eigen::Matrix<double, 12, 1>& f, double normal) {
    const int side_a = mesh.vertex_body[vertex[0]];
    const int side_b = mesh.vertex_body[vertex[edge_edge ? 2 : 1]];
    if (side_a == side_b) return;  // self-contact: internal to the body
    const int first = std::min(side_a, side_b), second = std::max(side_a, side_b);
    PairForce& pf = forces[{first, second}];
    pf.body_a = first;
    pf.body_b = second;
    pf.normal_force += normal;
    for (int i = 0; i < 4; ++i) {
      if (mesh.vertex_body[vertex[i]] == first) pf.force += f.segment<3>(3 * i);
    }
  };
  for (const ContactCandidate& c : near) {
    const ContactForce force = potential.barrier().contact_force(c, positions);
    // Pairs near at rest have no barrier: their distance would drive kappa's adaptation.
    if (!c.near_at_rest && force.distance < model.sim().d_hat) {
      min_distance = std::min(min_distance, force.distance);
    }
    if (force.magnitude > 0.0) add(c.vertex, c.edge_edge, force.force, force.magnitude);
  }
  for (const FrictionContact& contact : potential.friction().contacts()) {
    add(contact.vertex, contact.edge_edge, potential.friction().force(contact, positions), 0.0);
  }
  std::vector<PairForce> result;
  for (const auto& [key, pf] : forces) result.push_back(pf);
  return result;
}

}  // namespace grip::solver
