// The data-parallel engine's affine-body stages (solver/parallel/affine_stages.hpp: prediction,
// inertia, orthogonality, drive) on the host launchers, against the CPU engine's AffineBodies
// and DrivenBodies on the same states: a batch of environments of two models that mix affine,
// driven, FEM and kinematic bodies, the affine matrices pushed off rotations. Also: gradients
// against central differences of the stages' energies, the serial and TBB launchers agree bit
// for bit, and an environment's values do not depend on the others in its batch.
#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <random>
#include <vector>

#include "solver/batch/model_batch.hpp"
#include "solver/batch/tbb_launcher.hpp"
#include "solver/body/affine_bodies.hpp"
#include "solver/environment.hpp"
#include "solver/parallel/affine_stages.hpp"
#include "solver/parallel/elastic_stages.hpp"
#include "solver/parallel/launch.hpp"
#include "tests/solver/scene_builders.hpp"

namespace grip::solver {
namespace {

using parallel::AffineBatch;

// One body of each kind, the affine ones after an FEM one.
std::shared_ptr<const Model> mixed_scene() { return Model::build(testing::every_kind_of_body()); }

// A turned box of other density and stiffness, and a stiffer driven cube.
std::shared_ptr<const Model> turned_scene() {
  SceneDescription scene;
  BodyDescription box =
      testing::rigid_box("box", BodyType::kAffine, {0.05, 0.02, 0.02}, {0.0, 0.1, 0.1});
  box.pose.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  box.material.density = 2500.0;
  box.orthogonality_stiffness *= 3.0;
  scene.bodies = {box, testing::driven_cube("link", {0.1, 0.1, 0.1}, 5e4)};
  return Model::build(scene);
}

struct Batch {
  std::vector<std::shared_ptr<const Model>> models;
  AffineBatch affine;
  std::vector<double> q, v, target;  // every environment's DOFs, one after the other
  std::vector<double> h, gravity;    // per environment
};

// Each environment's start DOFs with every affine matrix scaled by 0.75 to 1.2 per axis and
// jittered (so that some orthogonality Hessians need projecting), random velocities, and drive
// targets a few millimetres and degrees off the state.
Batch make_batch(const std::vector<std::shared_ptr<const Model>>& models) {
  Batch b;
  b.models = models;
  std::vector<const Model*> environments;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (std::size_t e = 0; e < models.size(); ++e) {
    environments.push_back(models[e].get());
    Eigen::VectorXd q = Environment(models[e]).dofs();
    const std::size_t first = b.q.size();
    for (const BodyModel& body : models[e]->bodies()) {
      if (body.dof_count != 12) continue;
      for (int k = 3; k < 12; ++k) {
        q[body.dof_offset + k] *= 0.975 + 0.225 * unit(random);
        q[body.dof_offset + k] += 0.1 * unit(random);
      }
    }
    b.q.insert(b.q.end(), q.data(), q.data() + q.size());
    for (Eigen::Index d = 0; d < q.size(); ++d) {
      b.v.push_back(0.3 * unit(random));
      b.target.push_back(b.q[first + d] + 0.005 * unit(random));
    }
    b.h.push_back(e % 2 ? 0.005 : 0.01);
    b.gravity.insert(b.gravity.end(), {0.5 * unit(random), 0.0, -9.81});
  }
  b.affine = parallel::affine_batch(environments);
  return b;
}

struct Values {
  std::vector<double> q_tilde;
  std::vector<double> inertia_energy, orthogonality_energy, drive_energy;        // per body
  std::vector<double> inertia_gradient, orthogonality_gradient, drive_gradient;  // batch DOFs
  std::vector<double> hessian;                                                   // 81 per body
};

template <class Launcher>
Values run_stages(const Batch& b, Launcher&& launch, bool project = true) {
  const parallel::AffineBuffers bodies = b.affine.bodies();
  const std::size_t n = static_cast<std::size_t>(bodies.count), dofs = b.q.size();
  Values v{std::vector<double>(dofs), std::vector<double>(n),     std::vector<double>(n),
           std::vector<double>(n),    std::vector<double>(dofs),  std::vector<double>(dofs),
           std::vector<double>(dofs), std::vector<double>(81 * n)};
  launch(bodies.count, parallel::AffinePredictionStage{bodies, b.q.data(), b.v.data(), b.h.data(),
                                                       b.gravity.data(), v.q_tilde.data()});
  // The inertia term at the state after the step: the start state moved by its velocity.
  std::vector<double> q_end(dofs);
  for (std::size_t d = 0; d < dofs; ++d) q_end[d] = b.q[d] + 0.004 * b.v[d];
  launch(bodies.count,
         parallel::AffineInertiaStage{bodies, q_end.data(), v.q_tilde.data(),
                                      v.inertia_energy.data(), v.inertia_gradient.data()});
  launch(bodies.count,
         parallel::OrthogonalityStage{bodies, b.q.data(), project, v.orthogonality_energy.data(),
                                      v.orthogonality_gradient.data(), v.hessian.data()});
  launch(bodies.count, parallel::DriveStage{bodies, b.q.data(), b.target.data(),
                                            v.drive_energy.data(), v.drive_gradient.data()});
  return v;
}

// |a - b| at most `relative` times the largest |b| of the range.
void expect_close(const double* a, const double* b, int n, double relative) {
  double scale = 0.0, difference = 0.0;
  for (int k = 0; k < n; ++k) {
    scale = std::max(scale, std::abs(b[k]));
    difference = std::max(difference, std::abs(a[k] - b[k]));
  }
  EXPECT_GT(scale, 0.0);
  EXPECT_LE(difference, relative * scale);
}

const AffineBodies& affine_kind(const BodyModel& body) {
  return dynamic_cast<const AffineBodies&>(*body.kind);
}

TEST(ParallelAffine, BuffersHoldTheCpuEnginesBodies) {
  const Batch b = make_batch({mixed_scene(), turned_scene(), mixed_scene()});
  ASSERT_EQ(b.affine.environment_count(), 3);
  const std::vector<int> body_begin{0, 2, 4, 6};
  EXPECT_EQ(b.affine.body_begin(), body_begin);
  int i = 0;
  for (int e = 0; e < 3; ++e) {
    for (const BodyModel& body : b.models[e]->bodies()) {
      if (body.dof_count != 12) continue;
      const AffineBodies& kind = affine_kind(body);
      const bool driven = body.scripted();
      EXPECT_EQ(b.affine.dof()[i], b.affine.dof_begin()[e] + body.dof_offset);
      EXPECT_TRUE(std::equal(kind.mass_matrix(body.local).data(),
                             kind.mass_matrix(body.local).data() + 144,
                             b.affine.mass_matrix().begin() + 144 * i));
      EXPECT_EQ(b.affine.weight_mass()[i],
                driven ? 0.0 : kind.density(body.local) * kind.volume(body.local));
      EXPECT_EQ(b.affine.drive_stiffness()[i] > 0.0, driven);
      ++i;
    }
  }
}

TEST(ParallelAffine, StagesMatchTheCpuEngineOnEveryBody) {
  const Batch b = make_batch({mixed_scene(), turned_scene(), mixed_scene()});
  const Values v = run_stages(b, parallel::SerialLauncher{});
  int i = 0;
  for (int e = 0; e < 3; ++e) {
    const Model& model = *b.models[e];
    const int first = b.affine.dof_begin()[e], n = model.dof_count();
    const Eigen::Map<const Eigen::VectorXd> q(b.q.data() + first, n), vel(b.v.data() + first, n),
        target(b.target.data() + first, n);
    Eigen::VectorXd q_tilde = q + b.h[e] * vel;
    const Eigen::VectorXd q_end = q + 0.004 * vel;
    for (const BodyModel& body : model.bodies()) {
      if (body.dof_count != 12) continue;
      SCOPED_TRACE("environment " + std::to_string(e) + ", body " + body.name);
      const BodySubsystem& kind = *body.kind;
      const int o = body.dof_offset, l = body.local;
      kind.add_gravity(l, Eigen::Vector3d(&b.gravity[3 * e]), b.h[e], q_tilde);
      expect_close(&v.q_tilde[first + o], &q_tilde[o], 12, 1e-15);

      double inertia = 0.0, orthogonality = 0.0, drive = 0.0;
      Eigen::VectorXd g_inertia = Eigen::VectorXd::Zero(n), g_orthogonality = g_inertia,
                      g_drive = g_inertia;
      Triplets triplets;
      kind.add_inertia_energy(l, q_end, q_tilde, inertia);
      kind.add_inertia_derivatives(l, q_end, q_tilde, 1.0, g_inertia, nullptr);
      kind.add_elastic_energy(l, q, orthogonality);
      kind.add_elastic_derivatives(l, q, 1.0, nullptr, g_orthogonality, &triplets);
      if (body.scripted()) {
        kind.add_drive_energy(l, q, target, drive);
        kind.add_drive_derivatives(l, q, target, 1.0, g_drive, nullptr);
      }
      EXPECT_GT(inertia, 0.0);
      EXPECT_NEAR(v.inertia_energy[i], inertia, 1e-14 * inertia);
      expect_close(&v.inertia_gradient[first + o], &g_inertia[o], 12, 1e-14);
      // The same kernels as the CPU engine's: bit for bit.
      EXPECT_GT(orthogonality, 0.0);
      EXPECT_EQ(v.orthogonality_energy[i], orthogonality);
      for (int k = 0; k < 12; ++k)
        EXPECT_EQ(v.orthogonality_gradient[first + o + k], g_orthogonality[o + k]);
      // The projected block against the CPU engine's (Eigen's eigen-solver; Jacobi rotations here).
      Eigen::SparseMatrix<double> lower(n, n);
      lower.setFromTriplets(triplets.begin(), triplets.end());
      const Eigen::MatrixXd cpu = Eigen::MatrixXd(lower).selfadjointView<Eigen::Lower>();
      const Eigen::Map<const Eigen::Matrix<double, 9, 9>> block(&v.hessian[81 * i]);
      EXPECT_LE((block - cpu.block<9, 9>(o + 3, o + 3)).norm(), 1e-13 * block.norm());
      EXPECT_EQ((cpu.block<3, 12>(o, o).norm()), 0.0);
      EXPECT_EQ(v.drive_energy[i] > 0.0, body.scripted());
      if (body.scripted()) {
        EXPECT_NEAR(v.drive_energy[i], drive, 1e-14 * drive);
        expect_close(&v.drive_gradient[first + o], &g_drive[o], 12, 1e-14);
      }
      ++i;
    }
  }
  EXPECT_EQ(i, b.affine.bodies().count);
}

TEST(ParallelAffine, SomeOrthogonalityHessiansNeededTheirProjection) {
  // Otherwise the comparison above would not cover the projection.
  const Batch b = make_batch({mixed_scene(), turned_scene(), mixed_scene()});
  const Values projected = run_stages(b, parallel::SerialLauncher{}, true);
  const Values exact = run_stages(b, parallel::SerialLauncher{}, false);
  int changed = 0;
  for (int i = 0; i < b.affine.bodies().count; ++i) {
    changed +=
        !std::equal(projected.hessian.begin() + 81 * i, projected.hessian.begin() + 81 * (i + 1),
                    exact.hessian.begin() + 81 * i);
  }
  EXPECT_GT(changed, 0);
}

// The three energies of environment e summed, the DOFs of the batch at q.
double total_energy(const Batch& b, const std::vector<double>& q, int e) {
  Batch at = b;
  at.q = q;
  const Values v = run_stages(at, parallel::SerialLauncher{});
  double sum = 0.0;
  for (int i = b.affine.body_begin()[e]; i < b.affine.body_begin()[e + 1]; ++i) {
    sum += v.orthogonality_energy[i] + v.drive_energy[i];
  }
  return sum;
}

TEST(ParallelAffine, GradientsMatchCentralDifferences) {
  // Orthogonality and drive in q (the inertia gradient is M dq, compared above).
  const Batch b = make_batch({mixed_scene(), turned_scene()});
  const Values v = run_stages(b, parallel::SerialLauncher{});
  for (int i = 0; i < b.affine.bodies().count; ++i) {
    const int e = b.affine.environment()[i], dof = b.affine.dof()[i];
    for (int k = 0; k < 12; ++k) {
      const double step = 1e-6;
      std::vector<double> plus = b.q, minus = b.q;
      plus[dof + k] += step;
      minus[dof + k] -= step;
      const double numeric = (total_energy(b, plus, e) - total_energy(b, minus, e)) / (2 * step);
      const double analytic = v.orthogonality_gradient[dof + k] + v.drive_gradient[dof + k];
      EXPECT_NEAR(analytic, numeric, 1e-6 * std::max(1.0, std::abs(analytic)))
          << "body " << i << ", DOF " << k;
    }
  }
}

TEST(ParallelAffine, TbbAndSerialLaunchersAgreeBitForBit) {
  const Batch b = make_batch({mixed_scene(), turned_scene(), mixed_scene()});
  const Values serial = run_stages(b, parallel::SerialLauncher{});
  const Values threaded = run_stages(b, parallel::TbbLauncher(2));
  EXPECT_EQ(serial.q_tilde, threaded.q_tilde);
  EXPECT_EQ(serial.inertia_gradient, threaded.inertia_gradient);
  EXPECT_EQ(serial.orthogonality_energy, threaded.orthogonality_energy);
  EXPECT_EQ(serial.hessian, threaded.hessian);
  EXPECT_EQ(serial.drive_gradient, threaded.drive_gradient);
}

TEST(ParallelAffine, AnEnvironmentsValuesDoNotDependOnItsBatch) {
  const auto a = turned_scene(), c = mixed_scene();
  const Batch three = make_batch({a, c, a});
  const Batch alone = make_batch({a});
  const Values in_batch = run_stages(three, parallel::SerialLauncher{});
  const Values solo = run_stages(alone, parallel::SerialLauncher{});
  const std::size_t dofs = static_cast<std::size_t>(a->dof_count());
  EXPECT_TRUE(
      std::equal(solo.q_tilde.begin(), solo.q_tilde.begin() + dofs, in_batch.q_tilde.begin()));
  EXPECT_TRUE(std::equal(solo.hessian.begin(), solo.hessian.end(), in_batch.hessian.begin()));
  EXPECT_EQ(solo.drive_energy[1], in_batch.drive_energy[1]);
}

}  // namespace
}  // namespace grip::solver
