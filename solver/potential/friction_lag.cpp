#include "solver/potential/friction_lag.hpp"

#include "solver/kernels/contact_frame.hpp"

namespace grip::solver {

std::vector<FrictionContact> lag_friction(const BarrierTerm& barrier, const Vertices& positions,
                                          const std::vector<ContactCandidate>& near,
                                          bool at_zero_mu) {
  std::vector<FrictionContact> contacts;
  for (const ContactCandidate& c : near) {
    if (c.friction <= 0.0 && !at_zero_mu) continue;  // none where mu = 0
    const ContactForce force = barrier.contact_force(c, positions);
    if (force.magnitude <= 0.0) continue;
    Eigen::Vector3d x[4];
    for (int i = 0; i < 4; ++i) x[i] = positions.row(c.vertex[i]);
    const kernels::ContactFrame frame =
        c.edge_edge ? kernels::edge_edge_frame(x) : kernels::point_triangle_frame(x);
    contacts.push_back(
        {c.vertex, c.edge_edge, c.friction * force.magnitude, frame.tangent_operator()});
  }
  return contacts;
}

}  // namespace grip::solver
