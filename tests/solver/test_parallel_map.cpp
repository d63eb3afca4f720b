// The data-parallel engine's map between DOFs and collision vertices (solver/parallel/
// map_stages.hpp) and its Newton matrix in 3x3 blocks (block_assembly.hpp) on the host
// launchers, against the CPU engine's collision_positions, Stencil and terms: a batch of
// environments of two models that mix scripted, FEM, affine and driven bodies, the DOFs moved off
// their start (affine matrices off rotations), the scripted floor part way to its target; random
// contact pairs with random position-space gradients and Hessians. Also: the incidence lists
// every slot of a vertex with DOFs once, the serial and TBB launchers agree bit for bit, and an
// environment's values do not depend on its batch.
#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <set>
#include <vector>

#include "solver/batch/tbb_launcher.hpp"
#include "solver/parallel/map_stages.hpp"
#include "tests/solver/parallel_batch.hpp"

namespace grip::solver {
namespace {

using testing::add_cpu_pair_hessians;
using testing::assemble_newton_matrix;
using testing::Assembled;
using testing::Batch;
using testing::environment_lower;
using testing::kPairsPerEnvironment;
using testing::kProgress;
using testing::make_batch;
using testing::mixed_scene;
using testing::soft_scene;

struct Values {
  std::vector<double> x;         // 3 per collision vertex
  std::vector<double> gradient;  // the batch's DOFs
};

template <class Launcher>
Values run_stages(const Batch& b, Launcher&& launch) {
  Values v{std::vector<double>(3 * static_cast<std::size_t>(b.collision.vertex_count())),
           std::vector<double>(b.q.size(), 0.0)};
  launch(b.collision.vertex_count(),
         parallel::PositionStage{b.collision.vertices(), b.q.data(), b.start.data(),
                                 b.target.data(), b.progress.data(), v.x.data()});
  const int pairs = static_cast<int>(b.pair_vertex.size() / 4);
  const parallel::ContactIncidence incidence =
      parallel::contact_incidence(b.collision, b.pair_vertex.data(), pairs);
  launch(b.collision.block_count(),
         parallel::ContactGatherStage{parallel::incidence_buffers(b.collision, incidence),
                                      b.pair_vertex.data(), b.collision.rest().data(),
                                      b.pair_gradient.data(), v.gradient.data()});
  return v;
}

TEST(ParallelMap, PositionsMatchTheCpuEngineBitForBit) {
  const Batch b = make_batch({mixed_scene(), soft_scene(), mixed_scene()});
  const Values v = run_stages(b, parallel::SerialLauncher{});
  for (int e = 0; e < 3; ++e) {
    SCOPED_TRACE("environment " + std::to_string(e));
    const Vertices cpu = collision_positions(*b.models[e], b.states[e], b.targets[e], kProgress);
    const int first = b.collision.vertex_begin()[e];
    ASSERT_EQ(cpu.rows(), b.collision.vertex_begin()[e + 1] - first);
    for (Eigen::Index i = 0; i < cpu.rows(); ++i) {
      for (int k = 0; k < 3; ++k) ASSERT_EQ(v.x[3 * (first + i) + k], cpu(i, k)) << "vertex " << i;
    }
    // The floor moved part of the way, so the scripted rows were not a copy of either end.
    EXPECT_NE(b.targets[e].kinematic_start, b.targets[e].kinematic_target);
  }
}

TEST(ParallelMap, GatheredGradientsMatchTheCpuEnginesStencils) {
  const Batch b = make_batch({mixed_scene(), soft_scene(), mixed_scene()});
  const Values v = run_stages(b, parallel::SerialLauncher{});
  for (int e = 0; e < 3; ++e) {
    SCOPED_TRACE("environment " + std::to_string(e));
    const Model& model = *b.models[e];
    const int first_vertex = b.collision.vertex_begin()[e];
    Eigen::VectorXd cpu = Eigen::VectorXd::Zero(model.dof_count());
    for (int k = e * kPairsPerEnvironment; k < (e + 1) * kPairsPerEnvironment; ++k) {
      std::array<int, 4> vertex;
      for (int c = 0; c < 4; ++c) vertex[c] = b.pair_vertex[4 * k + c] - first_vertex;
      const Stencil::Vector12 g(&b.pair_gradient[12 * k]);
      Stencil(model, vertex).scatter_gradient(g, cpu);
    }
    const Eigen::Map<const Eigen::VectorXd> gathered(v.gradient.data() + b.collision.dof_begin()[e],
                                                     model.dof_count());
    EXPECT_GT(cpu.lpNorm<Eigen::Infinity>(), 0.0);
    EXPECT_LE((gathered - cpu).lpNorm<Eigen::Infinity>(), 1e-14 * cpu.lpNorm<Eigen::Infinity>());
  }
}

TEST(ParallelMap, EverySlotOfAVertexWithDofsIsInOneBlock) {
  const Batch b = make_batch({mixed_scene(), soft_scene()});
  const int pairs = static_cast<int>(b.pair_vertex.size() / 4);
  const parallel::ContactIncidence incidence =
      parallel::contact_incidence(b.collision, b.pair_vertex.data(), pairs);
  std::vector<int> seen(4 * static_cast<std::size_t>(pairs), 0);
  int scripted = 0;
  for (int block = 0; block < b.collision.block_count(); ++block) {
    for (int s = incidence.begin[block]; s < incidence.begin[block + 1]; ++s) {
      const int slot = incidence.slots[s];
      ++seen[slot];
      EXPECT_EQ(b.collision.block()[b.pair_vertex[slot]], block);
      if (s > incidence.begin[block]) {
        EXPECT_LT(incidence.slots[s - 1], slot);
      }
    }
  }
  for (std::size_t slot = 0; slot < seen.size(); ++slot) {
    const bool has_dofs = b.collision.block()[b.pair_vertex[slot]] >= 0;
    scripted += !has_dofs;
    EXPECT_EQ(seen[slot], has_dofs ? 1 : 0) << "slot " << slot;
  }
  EXPECT_GT(scripted, 0);  // the floor's vertices were drawn too
}

template <class Launcher>
Assembled assemble(const Batch& b, Launcher&& launch) {
  Assembled out;
  parallel::StencilSlots slots;
  parallel::add_contact_stencils(b.collision, b.pair_vertex.data(),
                                 static_cast<int>(b.pair_vertex.size() / 4), slots);
  out.pattern = parallel::block_pattern(slots, b.collision.dof_begin());
  out.blocks.resize(9 * out.pattern.row.size());
  launch(static_cast<int>(out.pattern.row.size()),
         parallel::BlockAssemblyStage{out.pattern.buffers(), slots.rest.data(),
                                      b.pair_hessian.data(), out.blocks.data()});
  return out;
}

TEST(ParallelMap, HessianBlocksMatchTheCpuEnginesStencils) {
  const Batch b = make_batch({mixed_scene(), soft_scene(), mixed_scene()});
  const Assembled a = assemble(b, parallel::SerialLauncher{});
  for (int e = 0; e < 3; ++e) {
    SCOPED_TRACE("environment " + std::to_string(e));
    const Model& model = *b.models[e];
    Triplets triplets;
    add_cpu_pair_hessians(b, e, triplets);
    Eigen::SparseMatrix<double> cpu(model.dof_count(), model.dof_count());
    cpu.setFromTriplets(triplets.begin(), triplets.end());
    EXPECT_GT(cpu.norm(), 0.0);
    EXPECT_LE((environment_lower(b, a, e) - cpu).norm(), 1e-14 * cpu.norm());
  }
}

TEST(ParallelMap, TheNewtonMatrixInBlocksIsTheCpuEnginesHessian) {
  const Batch b = make_batch({mixed_scene(), soft_scene(), mixed_scene()});
  const Assembled a = assemble_newton_matrix(b);
  for (int e = 0; e < 3; ++e) {
    SCOPED_TRACE("environment " + std::to_string(e));
    const Model& model = *b.models[e];
    const Eigen::VectorXd& q = b.states[e];
    Eigen::VectorXd unused = Eigen::VectorXd::Zero(model.dof_count());
    Triplets triplets;
    for (const BodyModel& body : model.bodies()) {
      if (!body.has_dofs()) continue;
      body.kind->add_inertia_derivatives(body.local, q, q, 1.0, unused, &triplets);
      body.kind->add_elastic_derivatives(body.local, q, 1.0, nullptr, unused, &triplets);
      if (body.scripted())
        body.kind->add_drive_derivatives(body.local, q, q, 1.0, unused, &triplets);
    }
    add_cpu_pair_hessians(b, e, triplets);
    Eigen::SparseMatrix<double> cpu(model.dof_count(), model.dof_count());
    cpu.setFromTriplets(triplets.begin(), triplets.end());
    EXPECT_GT(cpu.norm(), 0.0);
    EXPECT_LE((environment_lower(b, a, e) - cpu).norm(), 1e-12 * cpu.norm());
  }
}

TEST(ParallelMap, TbbAndSerialLaunchersAgreeBitForBit) {
  const Batch b = make_batch({mixed_scene(), soft_scene(), mixed_scene()});
  const Values serial = run_stages(b, parallel::SerialLauncher{});
  const Values threaded = run_stages(b, parallel::TbbLauncher(2));
  EXPECT_EQ(serial.x, threaded.x);
  EXPECT_EQ(serial.gradient, threaded.gradient);
  EXPECT_EQ(assemble(b, parallel::SerialLauncher{}).blocks,
            assemble(b, parallel::TbbLauncher(2)).blocks);
}

TEST(ParallelMap, AnEnvironmentsValuesDoNotDependOnItsBatch) {
  const Batch three = make_batch({soft_scene(), mixed_scene(), soft_scene()});
  const Batch alone = make_batch({soft_scene()});
  const Values in_batch = run_stages(three, parallel::SerialLauncher{});
  const Values solo = run_stages(alone, parallel::SerialLauncher{});
  ASSERT_TRUE(
      std::equal(alone.pair_vertex.begin(), alone.pair_vertex.end(), three.pair_vertex.begin()));
  EXPECT_TRUE(std::equal(solo.x.begin(), solo.x.end(), in_batch.x.begin()));
  EXPECT_TRUE(std::equal(solo.gradient.begin(), solo.gradient.end(), in_batch.gradient.begin()));
  const Assembled solo_blocks = assemble(alone, parallel::SerialLauncher{});
  const Assembled batch_blocks = assemble(three, parallel::SerialLauncher{});
  EXPECT_EQ(solo_blocks.pattern.environment_begin[1], batch_blocks.pattern.environment_begin[1]);
  EXPECT_TRUE(std::equal(solo_blocks.blocks.begin(), solo_blocks.blocks.end(),
                         batch_blocks.blocks.begin()));
}

}  // namespace
}  // namespace grip::solver
