#include "bench/robustness/robustness_trials.hpp"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "src/geometry/boundary_surface.hpp"
#include "src/geometry/tetrahedralize.hpp"
#include "src/grippers/coarse_leap_hand.hpp"
#include "src/grippers/gripper_registry.hpp"
#include "src/objects/object_library.hpp"
#include "src/synth/object_spec.hpp"
#include "src/synth/prepared_object.hpp"
#include "src/synth/synthesize.hpp"
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/parallel_trial_scene.hpp"
#include "src/trial/trial.hpp"

namespace grip::bench {
namespace {

// The soft object's material is `grip trial --soft`'s default (rigid objects take the same
// density and friction). Its tets are coarser than `grip trial --soft`'s (8 mm, and two across
// the thinnest wall): at most kTetEdge, and one across the thinnest wall. A soft cup meshed
// as the trial meshes it costs 15 minutes per fin-ray trial; the solver's failures are what is
// counted here, not the stress field.
constexpr solver::Material kObjectMaterial{1000.0, 1e6, 0.4, 3.5};
constexpr double kTetEdge = 0.016;
constexpr double kProductionTetEdge = 0.008;  // `grip trial --tet-edge`'s default

// The grippers as simulated here, built once on first use.
const grippers::ParallelGripper& rigid_jaws() {
  static const grippers::ParallelGripper gripper =
      grippers::make_parallel_gripper(grippers::GripperKind::kParallelJaw);
  return gripper;
}

// The 80 mm fin-ray finger with one tet layer across its depth (4 in its own mesh): the cheap
// stand-in, as it was before the production finger took GRIP's size.
const grippers::ParallelGripper& coarse_fin_ray() {
  static const grippers::ParallelGripper gripper = [] {
    grippers::FinRayOptions options = grippers::fin_ray_80mm_options();
    options.layers = 1;
    return grippers::make_umi_soft_gripper(options);
  }();
  return gripper;
}

const grippers::HandModel& coarse_hand() {
  static const grippers::HandModel hand = grippers::coarse_leap_hand();
  return hand;
}

const grippers::ParallelGripper& production_fin_ray() {
  static const grippers::ParallelGripper gripper =
      grippers::make_parallel_gripper(grippers::GripperKind::kFinRay);
  return gripper;
}

const grippers::ParallelGripper& fine_fin_ray() {
  static const grippers::ParallelGripper gripper = [] {
    grippers::FinRayOptions options;
    options.layers = kFineFinRayLayers;
    options.edge_length = kFineFinRayEdge;
    return grippers::make_umi_soft_gripper(options);
  }();
  return gripper;
}

const grippers::HandModel& production_hand() {
  static const grippers::HandModel hand =
      grippers::make_hand(grippers::GripperKind::kLeap, grippers::HandSide::kRight);
  return hand;
}

// The largest of the values measured (NaN ones are phases never run); NaN if none was.
double largest_measured(const std::array<double, 6>& values) {
  double most = std::numeric_limits<double>::quiet_NaN();
  for (const double d : values) {
    if (!std::isnan(d)) most = std::isnan(most) ? d : std::max(most, d);
  }
  return most;
}

// The sum of the values measured (not NaN): 0 if none.
double measured_sum(const std::array<double, 6>& values) {
  double sum = 0.0;
  for (const double d : values) {
    if (!std::isnan(d)) sum += d;
  }
  return sum;
}

}  // namespace

std::string robustness_object_model(bool soft, bool production_models, double interior_growth) {
  if (!soft) return "rigid: one affine body";
  if (production_models) {
    return fmt::format(
        "soft: FEM, E {:g} MPa, nu {:g}, tets as grip trial --soft meshes them (at most {:g} mm "
        "at the surface, two across the thinnest wall; {})",
        kObjectMaterial.youngs / 1e6, kObjectMaterial.poisson, kProductionTetEdge * 1e3,
        interior_growth > 0 ? fmt::format("growing by {:g} m per m of depth", interior_growth)
                            : std::string("uniform inside"));
  }
  return fmt::format(
      "soft: FEM, E {:g} MPa, nu {:g}, tets of at most {:g} mm, one across the "
      "thinnest wall",
      kObjectMaterial.youngs / 1e6, kObjectMaterial.poisson, kTetEdge * 1e3);
}

std::vector<synth::Candidate> synthesize_candidates(const RobustnessSet& set, std::uint64_t seed,
                                                    int count) {
  const synth::PreparedObject prepared(synth::load_object(set.category, seed));
  // Coarse models' candidates are the 80 mm finger's, whose one-layer mesh runs them.
  return synth::synthesize(
             prepared, grippers::gripper_type(set.gripper),
             /*bimanual=*/false, synth::SynthesisParams{}, seed, count,
             set.production_models ? grippers::FinRayOptions{} : grippers::fin_ray_80mm_options())
      .candidates;
}

trial::TrialObject make_object(const RobustnessSet& set, std::uint64_t seed) {
  trial::TrialObject object;
  object.name = set.category;
  object.surface = synth::load_object(set.category, seed);
  object.material = kObjectMaterial;
  if (set.soft) {
    geometry::TetOptions options;
    if (set.production_models) {
      options.edge_length = synth::object_tet_edge(set.category, seed, 1.0, kProductionTetEdge);
      options.interior_growth = set.soft_interior_growth;
    } else {
      const objects::ObjectShape shape =
          objects::sample_shape(objects::parse_object_category(set.category), seed);
      options.edge_length = std::min(kTetEdge, objects::thinnest_feature(shape));
    }
    object.tets = geometry::tetrahedralize(object.surface, options, set.category);
    object.surface = geometry::boundary_surface(*object.tets);
  }
  return object;
}

const grippers::ParallelGripper& robustness_parallel_gripper(const RobustnessSet& set) {
  if (set.gripper != "fin-ray") return rigid_jaws();
  return set.fine_fin_ray        ? fine_fin_ray()
         : set.production_models ? production_fin_ray()
                                 : coarse_fin_ray();
}

RobustnessScene::RobustnessScene(const RobustnessSet& set, const trial::TrialObject& object,
                                 const trial::TrialParameters& parameters) {
  if (set.gripper == "leap") {
    scene_ = std::make_unique<trial::HandTrialScene>(
        object, set.production_models ? production_hand() : coarse_hand(), "leap", parameters);
  } else {
    scene_ = std::make_unique<trial::ParallelTrialScene>(object, robustness_parallel_gripper(set),
                                                         parameters);
  }
}

RobustnessScene::~RobustnessScene() = default;

const trial::TrialParameters& RobustnessScene::parameters() const { return scene_->parameters(); }

std::vector<trial::TrialOutcome> RobustnessScene::run(
    const std::vector<synth::Candidate>& candidates, int threads, bool full_trials) const {
  trial::TrialRunOptions options;
  options.threads = threads;
  options.full_trials = full_trials;
  options.trajectory = false;
  return trial::run_trials(*scene_, candidates, options);
}

RobustnessTrial robustness_trial(const RobustnessSet& set, std::uint64_t seed, std::uint64_t k,
                                 const trial::TrialOutcome& outcome,
                                 const trial::TrialParameters& parameters) {
  const io::CandidateRecord& record = outcome.result.record;
  return {set.gripper,
          set.category,
          seed,
          set.soft,
          k,
          record.status,
          record.failure,
          outcome.failure_reason,
          record.newton,
          outcome.steps_by_newton_iterations,
          record.closing_forces,
          outcome.closed,
          outcome.settle_displacement,
          largest_measured(record.displacement),
          trial::slip_over_threshold(parameters, record.displacement, record.phase_seconds),
          largest_measured(outcome.center_displacement),
          largest_measured(outcome.end_speed),
          measured_sum(record.phase_seconds)};
}

}  // namespace grip::bench
