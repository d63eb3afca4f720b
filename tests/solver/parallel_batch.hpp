#pragma once
// A batch of the data-parallel engine's environments for the map, assembly and linear-solve
// tests: environments of two models that mix scripted, FEM, affine and driven bodies, the DOFs
// moved off their start (affine matrices off rotations), the scripted floor part way to its
// target; random contact pairs with random position-space gradients and Hessians; and the whole
// Newton matrix of such a batch in 3x3 blocks.
#include <Eigen/Sparse>
#include <algorithm>
#include <array>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "solver/batch/model_batch.hpp"
#include "solver/environment.hpp"
#include "solver/newton/step_targets.hpp"
#include "solver/parallel/affine_stages.hpp"
#include "solver/parallel/block_assembly.hpp"
#include "solver/parallel/elastic_stages.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/potential/stencil.hpp"
#include "tests/solver/scene_builders.hpp"

namespace grip::solver::testing {

inline std::shared_ptr<const Model> mixed_scene() { return Model::build(every_kind_of_body()); }

// Two soft boxes and a turned affine box over a scripted floor.
inline std::shared_ptr<const Model> soft_scene() {
  SceneDescription scene = every_kind_of_body();
  scene.bodies[2].pose.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  scene.bodies[3] = soft_box("soft 2", {0.02, 0.02, 0.03}, 0.01, {-0.1, 0, 0.05}, 1e6);
  return Model::build(scene);
}

inline constexpr int kPairsPerEnvironment = 60;
inline constexpr double kProgress = 0.3;

struct Batch {
  std::vector<std::shared_ptr<const Model>> models;
  parallel::CollisionBatch collision;
  parallel::FemBatch fem;
  parallel::AffineBatch affine;
  std::vector<Eigen::VectorXd> states;
  std::vector<StepTargets> targets;
  std::vector<double> q, start, target, progress;  // the batch's DOFs; scripted vertices' rows
  std::vector<int> pair_vertex;                    // 4 per pair, the batch's numbering
  std::vector<double> pair_gradient;               // 12 per pair
  std::vector<double> pair_hessian;                // 144 per pair, symmetric
};

// Each environment's DOFs moved at random (affine matrices by up to 10 %), its scripted floor's
// step targets, and random pairs of four distinct collision vertices on at most two bodies,
// with random gradients.
inline Batch make_batch(const std::vector<std::shared_ptr<const Model>>& models) {
  Batch b;
  b.models = models;
  std::vector<const Model*> environments;
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const auto& model : models) {
    environments.push_back(model.get());
    const Environment env(model);
    Eigen::VectorXd q = env.dofs();
    for (Eigen::Index d = 0; d < q.size(); ++d) q[d] += 0.01 * unit(random);
    b.states.push_back(q);
    b.q.insert(b.q.end(), q.data(), q.data() + q.size());
    b.targets.push_back(step_targets(*model, env.state(), 0.01));
    const StepTargets& t = b.targets.back();
    b.start.insert(b.start.end(), t.kinematic_start.data(),
                   t.kinematic_start.data() + t.kinematic_start.size());
    b.target.insert(b.target.end(), t.kinematic_target.data(),
                    t.kinematic_target.data() + t.kinematic_target.size());
    b.progress.push_back(kProgress);
  }
  b.collision = parallel::collision_batch(environments);
  b.fem = parallel::fem_batch(environments);
  b.affine = parallel::affine_batch(environments);
  for (int e = 0; e < b.collision.environment_count(); ++e) {
    const CollisionMesh& mesh = models[e]->collision();
    std::mt19937 pairs_random(100 + e);  // an environment's pairs whatever its batch
    std::uniform_int_distribution<int> body(0, mesh.body_count() - 1);
    // A pair's vertices lie on two bodies (or one): a point and a triangle, or two edges.
    const auto on = [&](int of) {
      std::uniform_int_distribution<int> vertex(mesh.body_first_vertex[of],
                                                mesh.body_first_vertex[of + 1] - 1);
      return vertex(pairs_random);
    };
    for (int k = 0; k < kPairsPerEnvironment; ++k) {
      const int first_body = body(pairs_random), second_body = body(pairs_random);
      const int split = 1 + k % 2;
      std::set<int> four;
      while (static_cast<int>(four.size()) < split) four.insert(on(first_body));
      while (four.size() < 4) four.insert(on(second_body));
      for (const int v : four) b.pair_vertex.push_back(b.collision.vertex_begin()[e] + v);
      for (int c = 0; c < 12; ++c) b.pair_gradient.push_back(unit(pairs_random));
      Eigen::Matrix<double, 12, 12> h;
      for (double& x : h.reshaped()) x = unit(pairs_random);
      h = (h + h.transpose()).eval();
      b.pair_hessian.insert(b.pair_hessian.end(), h.data(), h.data() + 144);
    }
  }
  return b;
}

// The pairs' Hessians assembled in 3x3 blocks, and environment e's blocks as the lower triangle
// of a sparse matrix over its own DOFs.
struct Assembled {
  parallel::BlockPattern pattern;
  std::vector<double> blocks;  // 9 per block
};

// Environment e's blocks (9 per block of `pattern`) as the lower triangle of a sparse matrix over
// its own DOFs, [dof_begin[e], dof_begin[e + 1]) of the batch's.
inline Eigen::SparseMatrix<double> lower_triangle(const parallel::BlockPattern& pattern,
                                                  const std::vector<double>& blocks,
                                                  const std::vector<int>& dof_begin, int e) {
  const int first = dof_begin[e], n = dof_begin[e + 1] - first;
  Triplets triplets;
  for (int k = pattern.environment_begin[e]; k < pattern.environment_begin[e + 1]; ++k) {
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) {
        const int row = 3 * pattern.row[k] + r - first, col = 3 * pattern.column[k] + c - first;
        if (row >= col) triplets.emplace_back(row, col, blocks[9 * k + 3 * c + r]);
      }
    }
  }
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(triplets.begin(), triplets.end());
  return lower;
}

inline Eigen::SparseMatrix<double> environment_lower(const Batch& b, const Assembled& a, int e) {
  return lower_triangle(a.pattern, a.blocks, b.collision.dof_begin(), e);
}

// The CPU engine's lower-triangle triplets of environment e's pairs' Hessians (Stencil::scatter).
inline void add_cpu_pair_hessians(const Batch& b, int e, Triplets& triplets) {
  const Model& model = *b.models[e];
  const int first_vertex = b.collision.vertex_begin()[e];
  Eigen::VectorXd unused = Eigen::VectorXd::Zero(model.dof_count());
  for (int k = e * kPairsPerEnvironment; k < (e + 1) * kPairsPerEnvironment; ++k) {
    std::array<int, 4> vertex;
    for (int c = 0; c < 4; ++c) vertex[c] = b.pair_vertex[4 * k + c] - first_vertex;
    const Stencil::Matrix12 h(&b.pair_hessian[144 * k]);
    Stencil(model, vertex).scatter(Stencil::Vector12::Zero(), h, unused, triplets);
  }
}

// Every term's Hessian of the batch's state in blocks: tets (projected), affine bodies (inertia,
// projected orthogonality, drive), the pairs' random ones, and the FEM vertices' masses.
inline Assembled assemble_newton_matrix(const Batch& b) {
  parallel::SerialLauncher launch;
  const parallel::TetBuffers tets = b.fem.tets();
  const parallel::AffineBuffers bodies = b.affine.bodies();
  const int pairs = static_cast<int>(b.pair_vertex.size() / 4);
  std::vector<double> hessian(144 * static_cast<std::size_t>(tets.count + bodies.count + pairs));
  std::vector<double> scratch(12 * static_cast<std::size_t>(tets.count)), gradient(b.q.size());
  launch(tets.count, parallel::ElasticStage{tets, b.q.data(), true, scratch.data(), scratch.data(),
                                            hessian.data()});
  std::vector<double> energy(bodies.count),
      orthogonality(81 * static_cast<std::size_t>(bodies.count));
  launch(bodies.count, parallel::OrthogonalityStage{bodies, b.q.data(), true, energy.data(),
                                                    gradient.data(), orthogonality.data()});
  launch(bodies.count, parallel::AffineHessianStage{bodies, orthogonality.data(),
                                                    hessian.data() + 144 * tets.count});
  std::copy(b.pair_hessian.begin(), b.pair_hessian.end(),
            hessian.begin() + 144 * (tets.count + bodies.count));
  parallel::StencilSlots slots;
  parallel::add_tet_stencils(b.fem, slots);
  parallel::add_affine_stencils(b.affine, slots);
  parallel::add_contact_stencils(b.collision, b.pair_vertex.data(), pairs, slots);
  Assembled out;
  out.pattern = parallel::block_pattern(slots, b.collision.dof_begin());
  out.blocks.resize(9 * out.pattern.row.size());
  launch(static_cast<int>(out.pattern.row.size()),
         parallel::BlockAssemblyStage{out.pattern.buffers(), slots.rest.data(), hessian.data(),
                                      out.blocks.data()});
  std::vector<int> units;
  for (const int dof : b.fem.vertex_dof()) units.push_back(dof / 3);
  const std::vector<int> diagonal = out.pattern.diagonal_blocks(units);
  launch(b.fem.vertices().count,
         parallel::MassDiagonalStage{b.fem.vertices(), diagonal.data(), out.blocks.data()});
  return out;
}

}  // namespace grip::solver::testing
