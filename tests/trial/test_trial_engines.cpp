// The trial protocol on the data-parallel engine (TrialRunOptions::device, solver/batch/
// engines.hpp) against the CPU engine: the same candidates, the same verdicts, IPC's D1 = 0.
// The engines' numerics differ (CG against CHOLMOD, docs/simulation.md), so what is compared is
// what the dataset labels: the verdict, the fingers' forces within the protocol's tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "src/geometry/primitives.hpp"
#include "src/grippers/parallel_gripper.hpp"
#include "src/trial/parallel_trial_scene.hpp"
#include "src/trial/trial.hpp"
#include "tests/trial/short_trial.hpp"

namespace grip::trial {
namespace {

using testing::parallel_candidates;
using testing::short_parameters;

// The object's centre 5 cm along the approach axis, jaws open 2.3 mm beyond its width.
ParallelGrasp centred(double width) {
  ParallelGrasp grasp;
  grasp.pose.translation() = Eigen::Vector3d(0.0, 0.0, -0.05);
  grasp.opening = width + 0.0046;
  return grasp;
}

std::vector<TrialOutcome> run_on(const TrialScene& scene, const std::vector<ParallelGrasp>& grasps,
                                 solver::EngineDevice device) {
  TrialRunOptions options;
  options.threads = 2;
  options.device = device;
  return run_trials(scene, parallel_candidates(grasps), options);
}

// Both engines' verdicts and D1 for the same candidates; each finger's closing force within the
// protocol's tolerance of the other engine's where the grasp closed on the object.
void expect_same_labels(const std::vector<TrialOutcome>& cpu, const std::vector<TrialOutcome>& host,
                        const TrialParameters& p) {
  ASSERT_EQ(host.size(), cpu.size());
  for (std::size_t k = 0; k < cpu.size(); ++k) {
    SCOPED_TRACE("candidate " + std::to_string(k));
    const io::CandidateRecord &c = cpu[k].result.record, &h = host[k].result.record;
    EXPECT_EQ(h.failure, c.failure) << io::to_string(h.failure) << " " << host[k].failure_reason;
    if (std::isnan(c.d1)) {
      EXPECT_TRUE(std::isnan(h.d1)) << "no D1 where the trial never closed";
    } else {
      EXPECT_EQ(h.d1, c.d1);
    }
    ASSERT_EQ(h.closing_forces.size(), c.closing_forces.size());
    for (std::size_t f = 0; f < c.closing_forces.size(); ++f) {
      EXPECT_NEAR(h.closing_forces[f], c.closing_forces[f], p.force_tolerance * p.grip_force);
    }
  }
}

// Rigid jaws (dense Cholesky on the data-parallel engine) on a cylinder: grasps that hold,
// slip without friction to speak of, miss and start inside.
TEST(TrialEngines, RigidJawsLabelAsOnTheCpuEngine) {
  TrialObject cylinder;
  cylinder.name = "cylinder";
  cylinder.surface = geometry::make_cylinder(0.02, 0.03, 24);
  cylinder.material.density = 500.0;
  cylinder.material.friction = 1.0;
  const TrialParameters p = short_parameters();
  const ParallelTrialScene scene(cylinder, grippers::make_rigid_jaw_gripper(), p);
  std::vector<ParallelGrasp> grasps;
  for (int k = 0; k < 4; ++k) {
    ParallelGrasp g = centred(0.04);
    g.pose.rotate(Eigen::AngleAxisd(0.1 * k, Eigen::Vector3d::UnitZ()));
    g.pose.pretranslate(Eigen::Vector3d(0.0, 0.0, -0.003 * k));
    grasps.push_back(g);
  }
  grasps[2].pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.05);  // on air
  grasps[3].opening = 0.03;                                        // inside the cylinder
  const std::vector<TrialOutcome> cpu = run_on(scene, grasps, solver::EngineDevice::kCpu);
  const std::vector<TrialOutcome> host = run_on(scene, grasps, solver::EngineDevice::kHost);
  expect_same_labels(cpu, host, p);
  EXPECT_EQ(host[0].result.record.failure, io::FailureKind::kNone);
  EXPECT_EQ(host[0].result.record.d1, 0.0);
  EXPECT_EQ(host[2].result.record.failure, io::FailureKind::kNoContact);
  EXPECT_EQ(host[3].result.record.failure, io::FailureKind::kInitialPenetration);
  EXPECT_GT(host[0].result.record.newton.iterations, 0u);
  EXPECT_EQ(host[0].linear_solves.cg_iterations, 0) << "rigid jaws: dense Cholesky";
}

// The one-layer fin-ray fingers (FEM: CG on the data-parallel engine) on a 4 cm box, centred
// and off centre: held on both engines, squeezed to the grip force.
TEST(TrialEngines, FinRayLabelsAsOnTheCpuEngine) {
  TrialObject box;
  box.name = "box";
  box.surface = geometry::make_box(Eigen::Vector3d(0.04, 0.03, 0.03));
  box.material.density = 500.0;
  box.material.friction = 3.5;
  TrialParameters p = short_parameters();
  p.squeeze_speed = 0.02;
  p.final_opening = 0.01;
  p.grip_force = 10.0;
  const ParallelTrialScene scene(box, testing::one_layer_fin_ray(), p);
  ParallelGrasp off = centred(0.04);
  off.pose.translation().x() = 0.01;
  const std::vector<ParallelGrasp> grasps{centred(0.04), off};
  const std::vector<TrialOutcome> cpu = run_on(scene, grasps, solver::EngineDevice::kCpu);
  const std::vector<TrialOutcome> host = run_on(scene, grasps, solver::EngineDevice::kHost);
  expect_same_labels(cpu, host, p);
  for (const TrialOutcome& outcome : host) {
    EXPECT_EQ(outcome.result.record.failure, io::FailureKind::kNone) << outcome.failure_reason;
    EXPECT_EQ(outcome.result.record.d1, 0.0);
    EXPECT_GT(outcome.linear_solves.cg_iterations, 0);
  }
}

}  // namespace
}  // namespace grip::trial
