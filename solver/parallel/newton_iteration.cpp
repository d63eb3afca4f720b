#include "solver/parallel/newton_iteration.hpp"

namespace grip::solver::parallel {

ContactPairs pairs_of(const HostBroadPhase& found, const std::vector<int>& list,
                      const std::vector<int>& list_begin, const std::vector<int>& vertex_begin,
                      const std::vector<double>& d_hat, const std::vector<double>& kappa) {
  ContactPairs pairs;
  for (std::size_t e = 0; e + 1 < list_begin.size(); ++e) {
    pairs.begin_environment(vertex_begin[e + 1] - vertex_begin[e], d_hat[e], kappa[e]);
    for (int k = list_begin[e]; k < list_begin[e + 1]; ++k) {
      const int c = list[k];
      if (found.near_at_rest()[c] != 0) continue;
      int vertex[4];
      for (int i = 0; i < 4; ++i) vertex[i] = found.vertex()[4 * c + i] - vertex_begin[e];
      pairs.add(found.edge_edge()[c] != 0, vertex, found.mollifier_eps()[c]);
    }
  }
  return pairs;
}

ContactPairs chosen_pairs(const ContactPairs& kept, const ContactPairs& fresh,
                          const std::vector<unsigned char>& take) {
  ContactPairs pairs;
  for (std::size_t e = 0; e < take.size(); ++e) {
    const ContactPairs& from = take[e] != 0 ? fresh : kept;
    const int first_vertex = from.vertex_begin()[e];
    pairs.begin_environment(from.vertex_begin()[e + 1] - first_vertex, from.d_hat()[e],
                            from.kappa()[e]);
    for (int k = from.pair_begin()[e]; k < from.pair_begin()[e + 1]; ++k) {
      int vertex[4];
      for (int i = 0; i < 4; ++i) vertex[i] = from.vertex()[4 * k + i] - first_vertex;
      pairs.add(from.edge_edge()[k] != 0, vertex, from.mollifier_eps()[k]);
    }
  }
  return pairs;
}

}  // namespace grip::solver::parallel
