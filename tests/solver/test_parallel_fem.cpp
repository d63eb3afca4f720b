// The data-parallel engine's FEM stages (solver/parallel/: elastic, inertia) on the host
// launchers, against the CPU engine's FEM terms (FemBodies) on the same states: a batch of
// environments of two models, each deformed differently. Also: the serial and TBB launchers
// agree bit for bit, and an environment's values do not depend on the others in its batch.
#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <random>
#include <vector>

#include "solver/batch/model_batch.hpp"
#include "solver/batch/tbb_launcher.hpp"
#include "solver/environment.hpp"
#include "solver/parallel/elastic_stages.hpp"
#include "solver/parallel/inertia_stages.hpp"
#include "solver/parallel/launch.hpp"
#include "tests/solver/scene_builders.hpp"

namespace grip::solver {
namespace {

using parallel::ElasticStage;
using parallel::EnvironmentSumStage;
using parallel::FemBatch;

// Two soft boxes of different materials beside an affine box, so that FEM DOFs do not start
// at 0 and bodies of other kinds sit between them.
std::shared_ptr<const Model> two_soft_boxes() {
  SceneDescription scene;
  BodyDescription rigid =
      testing::rigid_box("rigid", BodyType::kAffine, {0.02, 0.02, 0.02}, {0.0, 0.0, 0.2});
  scene.bodies = {testing::soft_box("soft", {0.03, 0.02, 0.02}, 0.01, {0, 0, 0}, 2e5), rigid,
                  testing::soft_box("stiff", {0.02, 0.02, 0.04}, 0.01, {0.1, 0, 0}, 9.4e6)};
  scene.bodies[2].material.poisson = 0.45;
  return Model::build(scene);
}

std::shared_ptr<const Model> one_soft_box() {
  SceneDescription scene;
  scene.bodies = {testing::soft_box("soft", {0.04, 0.03, 0.02}, 0.01, {0, 0, 0}, 1e6)};
  return Model::build(scene);
}

// The model's initial DOFs, its FEM vertices squeezed along z by `squeeze` and jittered by up to
// a third of a cell, so that some tets' Hessians need projecting.
Eigen::VectorXd deformed(const std::shared_ptr<const Model>& model, double squeeze, unsigned seed) {
  Eigen::VectorXd q = Environment(model).dofs();
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.003, 0.003);
  for (const BodyModel& body : model->bodies()) {
    if (!body.deforms()) continue;
    for (int d = 0; d < body.dof_count; ++d) {
      double& x = q[body.dof_offset + d];
      if (d % 3 == 2) x *= squeeze;
      x += jitter(random);
    }
  }
  return q;
}

struct Values {
  std::vector<double> energy;    // per environment
  std::vector<double> gradient;  // the batch's DOFs
  std::vector<double> hessian;   // 144 per tet
};

template <class Launcher>
Values run_stages(const FemBatch& batch, const std::vector<double>& q, Launcher&& launch) {
  const int tets = batch.tets().count;
  std::vector<double> tet_energy(tets), tet_gradient(12 * static_cast<std::size_t>(tets));
  Values v{std::vector<double>(batch.environment_count()), std::vector<double>(q.size(), 0.0),
           std::vector<double>(144 * static_cast<std::size_t>(tets))};
  parallel::launch_elastic_stages(launch, batch.tets(), batch.incidence(), batch.tet_begin().data(),
                                  batch.environment_count(), q.data(),
                                  {tet_energy.data(), tet_gradient.data(), v.hessian.data(),
                                   v.gradient.data(), v.energy.data()});
  return v;
}

struct Batch {
  std::vector<std::shared_ptr<const Model>> models;
  std::vector<Eigen::VectorXd> states;
  FemBatch fem;
  std::vector<double> q;  // every environment's DOFs, one after the other
};

Batch make_batch(const std::vector<std::shared_ptr<const Model>>& models) {
  Batch b;
  b.models = models;
  std::vector<const Model*> environments;
  for (std::size_t e = 0; e < models.size(); ++e) {
    environments.push_back(models[e].get());
    b.states.push_back(deformed(models[e], 1.0 - 0.15 * static_cast<double>(e), 7 + e));
    b.q.insert(b.q.end(), b.states.back().data(), b.states.back().data() + b.states.back().size());
  }
  b.fem = parallel::fem_batch(environments);
  return b;
}

// The CPU engine's elastic energy, gradient and (lower-triangle) Hessian of one environment's
// FEM bodies.
struct CpuTerms {
  double energy = 0.0;
  Eigen::VectorXd gradient;
  Eigen::SparseMatrix<double> lower;
};

CpuTerms cpu_terms(const Model& model, const Eigen::VectorXd& q) {
  CpuTerms t;
  t.gradient = Eigen::VectorXd::Zero(q.size());
  Triplets triplets;
  for (const BodyModel& body : model.bodies()) {
    if (!body.deforms()) continue;  // an affine body's orthogonality term is not the stage's
    body.kind->add_elastic_energy(body.local, q, t.energy);
    body.kind->add_elastic_derivatives(body.local, q, 1.0, nullptr, t.gradient, &triplets);
  }
  t.lower.resize(q.size(), q.size());
  t.lower.setFromTriplets(triplets.begin(), triplets.end());
  return t;
}

// The lower triangle of environment e's Hessian, scattered from the stage's per-tet blocks.
Eigen::SparseMatrix<double> batch_lower(const Batch& b, const Values& v, int e) {
  const int first_dof = b.fem.dof_begin()[e];
  const int dofs = b.fem.dof_begin()[e + 1] - first_dof;
  Triplets triplets;
  for (int t = b.fem.tet_begin()[e]; t < b.fem.tet_begin()[e + 1]; ++t) {
    for (int r = 0; r < 12; ++r) {
      for (int c = 0; c < 12; ++c) {
        const int row = b.fem.tet_dofs()[4 * t + r / 3] + r % 3 - first_dof;
        const int col = b.fem.tet_dofs()[4 * t + c / 3] + c % 3 - first_dof;
        if (row >= col) triplets.emplace_back(row, col, v.hessian[144 * t + 12 * c + r]);
      }
    }
  }
  Eigen::SparseMatrix<double> lower(dofs, dofs);
  lower.setFromTriplets(triplets.begin(), triplets.end());
  return lower;
}

TEST(ParallelElastic, StagesMatchTheCpuEngineOnEveryEnvironment) {
  const Batch b = make_batch({two_soft_boxes(), one_soft_box(), two_soft_boxes()});
  const Values v = run_stages(b.fem, b.q, parallel::SerialLauncher{});
  ASSERT_EQ(b.fem.environment_count(), 3);
  for (int e = 0; e < 3; ++e) {
    SCOPED_TRACE("environment " + std::to_string(e));
    const CpuTerms cpu = cpu_terms(*b.models[e], b.states[e]);
    EXPECT_GT(cpu.energy, 0.0);
    EXPECT_NEAR(v.energy[e], cpu.energy, 1e-12 * cpu.energy);
    const int first = b.fem.dof_begin()[e];
    const Eigen::Map<const Eigen::VectorXd> gradient(v.gradient.data() + first,
                                                     cpu.gradient.size());
    EXPECT_LE((gradient - cpu.gradient).lpNorm<Eigen::Infinity>(),
              1e-12 * cpu.gradient.lpNorm<Eigen::Infinity>());
    const Eigen::SparseMatrix<double> difference = batch_lower(b, v, e) - cpu.lower;
    EXPECT_GT(cpu.lower.norm(), 0.0);
    EXPECT_LE(difference.norm(), 1e-12 * cpu.lower.norm());
  }
}

TEST(ParallelElastic, SomeHessiansNeededTheirProjection) {
  // Otherwise the comparison above would not cover the projection.
  const Batch b = make_batch({two_soft_boxes(), one_soft_box(), two_soft_boxes()});
  std::vector<double> tet_energy(b.fem.tets().count), tet_gradient(12 * tet_energy.size());
  std::vector<double> projected(144 * tet_energy.size()), exact(projected.size());
  parallel::SerialLauncher launch;
  launch(b.fem.tets().count, ElasticStage{b.fem.tets(), b.q.data(), true, tet_energy.data(),
                                          tet_gradient.data(), projected.data()});
  launch(b.fem.tets().count, ElasticStage{b.fem.tets(), b.q.data(), false, tet_energy.data(),
                                          tet_gradient.data(), exact.data()});
  int changed = 0;
  for (std::size_t t = 0; t < tet_energy.size(); ++t) {
    changed += !std::equal(projected.begin() + 144 * t, projected.begin() + 144 * (t + 1),
                           exact.begin() + 144 * t);
  }
  EXPECT_GT(changed, 0);
}

TEST(ParallelElastic, TbbAndSerialLaunchersAgreeBitForBit) {
  const Batch b = make_batch({two_soft_boxes(), one_soft_box(), two_soft_boxes()});
  const Values serial = run_stages(b.fem, b.q, parallel::SerialLauncher{});
  const Values threaded = run_stages(b.fem, b.q, parallel::TbbLauncher(2));
  EXPECT_EQ(serial.energy, threaded.energy);
  EXPECT_EQ(serial.gradient, threaded.gradient);
  EXPECT_EQ(serial.hessian, threaded.hessian);
}

TEST(ParallelElastic, AnEnvironmentsValuesDoNotDependOnItsBatch) {
  const auto a = two_soft_boxes(), c = one_soft_box();
  const Batch three = make_batch({a, c, a});
  const Batch alone = make_batch({a});
  const Values in_batch = run_stages(three.fem, three.q, parallel::SerialLauncher{});
  const Values solo = run_stages(alone.fem, alone.q, parallel::SerialLauncher{});
  EXPECT_EQ(in_batch.energy[0], solo.energy[0]);
  EXPECT_TRUE(std::equal(solo.gradient.begin(), solo.gradient.end(), in_batch.gradient.begin()));
  EXPECT_TRUE(std::equal(solo.hessian.begin(), solo.hessian.end(), in_batch.hessian.begin()));
  EXPECT_EQ(three.fem.dof_begin()[1], a->dof_count());
  EXPECT_EQ(three.fem.dof_begin()[3], 2 * a->dof_count() + c->dof_count());
}

TEST(ParallelInertia, TargetsMassesAndTermsMatchTheCpuEngine) {
  const Batch b = make_batch({two_soft_boxes(), one_soft_box(), two_soft_boxes()});
  const int n = b.fem.environment_count();
  // Per environment a step and a gravity of its own; velocities at random.
  std::vector<double> h{0.01, 0.005, 0.02}, gravity{0, 0, -9.8, 9.8, 0, 0, 0, -9.8, 0};
  std::mt19937 random(11);
  std::uniform_real_distribution<double> speed(-0.5, 0.5);
  std::vector<double> v(b.q.size());
  for (double& x : v) x = speed(random);
  std::vector<double> q_tilde(b.q.size()), gradient(b.q.size());  // zeros
  std::vector<double> energy(b.fem.vertices().count), environment_energy(n);
  parallel::SerialLauncher launch;
  launch(b.fem.vertices().count,
         parallel::PredictionStage{b.fem.vertices(), b.q.data(), v.data(), h.data(), gravity.data(),
                                   q_tilde.data()});
  launch(b.fem.vertices().count,
         parallel::InertiaStage{b.fem.vertices(), b.q.data(), q_tilde.data(), energy.data(),
                                gradient.data()});
  launch(n, EnvironmentSumStage{b.fem.vertex_begin().data(), energy.data(),
                                environment_energy.data()});
  for (int e = 0; e < n; ++e) {
    SCOPED_TRACE("environment " + std::to_string(e));
    const Model& model = *b.models[e];
    const int first = b.fem.dof_begin()[e];
    const Eigen::Map<const Eigen::VectorXd> q(b.q.data() + first, model.dof_count()),
        velocity(v.data() + first, model.dof_count());
    Eigen::VectorXd cpu_target = q + h[e] * velocity;
    Eigen::VectorXd cpu_gradient = Eigen::VectorXd::Zero(model.dof_count());
    double cpu_energy = 0.0;
    for (const BodyModel& body : model.bodies()) {
      if (!body.deforms()) continue;
      body.kind->add_gravity(body.local, Eigen::Vector3d(&gravity[3 * e]), h[e], cpu_target);
      body.kind->add_inertia_energy(body.local, q, cpu_target, cpu_energy);
      body.kind->add_inertia_derivatives(body.local, q, cpu_target, 1.0, cpu_gradient, nullptr);
      const Eigen::VectorXd masses = body.kind->vertex_masses(body.local);
      for (int k = 0; k < body.dof_count; ++k) {
        const int dof = first + body.dof_offset + k;
        ASSERT_EQ(q_tilde[dof], cpu_target[body.dof_offset + k]) << "DOF " << dof;
        ASSERT_EQ(gradient[dof], cpu_gradient[body.dof_offset + k]) << "DOF " << dof;
      }
      // Vertex masses, in the batch's vertex order.
      const auto vertex = std::lower_bound(b.fem.vertex_dof().begin(), b.fem.vertex_dof().end(),
                                           first + body.dof_offset) -
                          b.fem.vertex_dof().begin();
      for (int i = 0; i < masses.size(); ++i) {
        EXPECT_EQ(b.fem.vertex_mass()[vertex + i], masses[i]);
      }
    }
    EXPECT_GT(cpu_energy, 0.0);
    EXPECT_NEAR(environment_energy[e], cpu_energy, 1e-13 * cpu_energy);
  }
}

}  // namespace
}  // namespace grip::solver
