#pragma once
// The contact forces of a configuration, as the trial and the dataset report them: per collision
// vertex, and summed per pair of bodies.
#include <Eigen/Core>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "solver/contact/candidates.hpp"
#include "solver/model/model.hpp"
#include "solver/potential/incremental_potential.hpp"

namespace grip::solver {

// The total contact force (barrier and friction) that body_b exerts on body_a, body_a < body_b.
struct PairForce {
  int body_a = -1;
  int body_b = -1;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // on body_a, N
  double normal_force = 0.0;  // sum of the contacts' barrier force magnitudes, N
};

// Contact forces summed per pair of distinct bodies, on the lower-numbered body; a body's
// contact with itself is internal to it and left out.
class PairForceSum {
 public:
  // The body of each collision vertex (CollisionMesh::vertex_body).
  explicit PairForceSum(const std::vector<int>& vertex_body) : vertex_body_(vertex_body) {}
  // A contact's force on its four collision vertices (`f`, 3 per vertex) and its normal force's
  // magnitude; side A is vertex[0]'s body, side B vertex[side_b]'s.
  void add(const int vertex[4], int side_b, const Eigen::Matrix<double, 12, 1>& f, double normal);
  // The pairs in (body_a, body_b) order.
  std::vector<PairForce> pairs() const;

 private:
  const std::vector<int>& vertex_body_;
  std::map<std::pair<int, int>, PairForce> forces_;
};

// Contact forces on each collision vertex (rows follow Model::collision()), N.
struct VertexContactForces {
  Vertices normal;    // barrier (normal) force
  Vertices friction;  // lagged friction force of the last step
};

// Barrier forces of the contacts at `positions` and the friction forces of the potential's
// lagged contacts there. `near` holds every pair within d_hat of `positions`, in
// find_contact_candidates' order (the sums follow it).
VertexContactForces vertex_contact_forces(const Model& model, const IncrementalPotential& potential,
                                          const Vertices& positions,
                                          const std::vector<ContactCandidate>& near);

// Per pair of distinct bodies, the forces as above, in (body_a, body_b) order; also the
// smallest distance over the contacts within d_hat (infinity without one). `near` holds every
// pair within d_hat of `positions` (find_contact_candidates).
std::vector<PairForce> pair_forces(const Model& model, const IncrementalPotential& potential,
                                   const Vertices& positions,
                                   const std::vector<ContactCandidate>& near, double& min_distance);

}  // namespace grip::solver
