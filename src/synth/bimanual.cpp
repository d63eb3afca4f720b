#include "src/synth/bimanual.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <stdexcept>

#include "src/synth/hand_energy.hpp"
#include "src/synth/kmeans.hpp"
#include "src/synth/triangle_tree.hpp"

namespace grip::synth {
namespace {

Points3 contact_centres(const std::vector<Candidate>& candidates) {
  Points3 centres(static_cast<int>(candidates.size()), 3);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    centres.row(static_cast<int>(i)) = candidates[i].hands.at(0).contacts.colwise().mean();
  }
  return centres;
}

struct Combination {
  int right;
  int left;
  double fc;
};

}  // namespace

std::vector<Candidate> compose_bimanual(
    const PreparedObject& object, const std::vector<Candidate>& right,
    const std::vector<Candidate>& left, int target, const BimanualParams& params,
    std::uint64_t seed,
    const std::function<geometry::SurfaceMesh(const Candidate&, bool left)>& posed,
    BimanualStatistics* statistics) {
  std::vector<Candidate> result;
  if (right.empty() || left.empty() || target <= 0) return result;
  for (const auto* set : {&right, &left}) {
    for (const Candidate& c : *set) {
      if (c.hands.size() != 1 || c.hands[0].contacts.rows() == 0) {
        throw std::invalid_argument(
            "compose_bimanual: every input candidate needs one hand with contacts");
      }
    }
  }
  const Clustering right_clusters = kmeans(contact_centres(right), params.clusters, seed);
  const Clustering left_clusters = kmeans(contact_centres(left), params.clusters, seed + 1);
  std::vector<std::vector<int>> right_members(
      static_cast<std::size_t>(right_clusters.centres.rows()));
  std::vector<std::vector<int>> left_members(
      static_cast<std::size_t>(left_clusters.centres.rows()));
  for (std::size_t i = 0; i < right.size(); ++i)
    right_members[static_cast<std::size_t>(right_clusters.labels[i])].push_back(
        static_cast<int>(i));
  for (std::size_t i = 0; i < left.size(); ++i)
    left_members[static_cast<std::size_t>(left_clusters.labels[i])].push_back(static_cast<int>(i));

  // Cluster pairs, farthest centres first; the top r1 of all k^2 pairs.
  struct ClusterPair {
    int right, left;
    double distance;
  };
  std::vector<ClusterPair> pairs;
  for (int a = 0; a < right_clusters.centres.rows(); ++a) {
    for (int b = 0; b < left_clusters.centres.rows(); ++b) {
      pairs.push_back(
          {a, b, (right_clusters.centres.row(a) - left_clusters.centres.row(b)).norm()});
    }
  }
  std::stable_sort(pairs.begin(), pairs.end(), [](const ClusterPair& x, const ClusterPair& y) {
    return x.distance > y.distance;
  });
  const auto kept_pairs = static_cast<std::size_t>(
      std::max(1.0, std::ceil(params.pair_fraction * static_cast<double>(pairs.size()))));
  pairs.resize(std::min(pairs.size(), kept_pairs));

  std::int64_t filtered = 0;
  for (const ClusterPair& p : pairs) {
    filtered += static_cast<std::int64_t>(right_members[static_cast<std::size_t>(p.right)].size() *
                                          left_members[static_cast<std::size_t>(p.left)].size());
  }
  BimanualStatistics stats;
  stats.filtered = filtered;
  const double keep_fraction = std::min(
      1.0, static_cast<double>(target) / static_cast<double>(std::max<std::int64_t>(filtered, 1)));

  std::vector<std::unique_ptr<TriangleTree>> right_trees(right.size());
  for (const ClusterPair& p : pairs) {
    std::vector<Combination> combinations;
    for (const int r : right_members[static_cast<std::size_t>(p.right)]) {
      for (const int l : left_members[static_cast<std::size_t>(p.left)]) {
        const HandGrasp& hr = right[static_cast<std::size_t>(r)].hands[0];
        const HandGrasp& hl = left[static_cast<std::size_t>(l)].hands[0];
        Points3 points(hr.contacts.rows() + hl.contacts.rows(), 3), normals(points.rows(), 3);
        points << hr.contacts, hl.contacts;
        normals << hr.contact_normals, hl.contact_normals;
        points.rowwise() -= object.centroid().transpose();
        combinations.push_back({r, l, force_closure_error(points, normals)});
      }
    }
    std::stable_sort(combinations.begin(), combinations.end(),
                     [](const Combination& x, const Combination& y) { return x.fc < y.fc; });
    // Rounding up keeps at least one from every selected pair; the total stops at the target.
    const auto quota = static_cast<std::size_t>(
        std::ceil(keep_fraction * static_cast<double>(combinations.size())));
    std::size_t taken = 0;
    for (const Combination& c : combinations) {
      if (taken >= quota || static_cast<int>(result.size()) >= target) break;
      const Candidate& cr = right[static_cast<std::size_t>(c.right)];
      const Candidate& cl = left[static_cast<std::size_t>(c.left)];
      auto& tree = right_trees[static_cast<std::size_t>(c.right)];
      if (!tree) tree = std::make_unique<TriangleTree>(posed(cr, false));
      ++stats.examined;
      if (tree->proximity(posed(cl, true), params.hand_clearance).distance <
          params.hand_clearance) {
        ++stats.colliding;
        continue;
      }
      Candidate both;
      both.gripper = cr.gripper;
      both.hands = {cr.hands[0], cl.hands[0]};
      both.energies.push_back({"fc_bimanual", c.fc});
      for (const EnergyTerm& t : cr.energies) both.energies.push_back({"right_" + t.name, t.value});
      for (const EnergyTerm& t : cl.energies) both.energies.push_back({"left_" + t.name, t.value});
      both.min_distance = std::min(cr.min_distance, cl.min_distance);
      result.push_back(std::move(both));
      ++taken;
    }
  }
  if (statistics) *statistics = stats;
  return result;
}

}  // namespace grip::synth
