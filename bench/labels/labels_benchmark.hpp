#pragma once
// `grip bench labels`: whether the trial protocol's verdicts are physics or numerics. The same
// synthesized candidates run at the defaults and at a refined reference (half the step, a
// Newton tolerance ten times tighter, two friction lag iterations), for rigid jaws on rigid
// objects, the fin-ray gripper on rigid and on soft objects and the LEAP hand on rigid objects;
// the verdicts must agree, and every finger in contact at the end of closing must hold the grip
// force.
#include <filesystem>
#include <string>
#include <vector>

#include "bench/robustness/robustness_benchmark.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::bench {

// What the reference refines; by default all three. Nothing: no reference runs, and the benchmark
// reports the defaults' verdicts and closing forces alone (a sweep over categories at a quarter
// of the cost).
struct LabelsRefinement {
  bool dt = true;            // divided by dt_divisor
  int dt_divisor = 2;        // a convergence study's finer references: 4, 8, ...
  bool newton_tol = true;    // divided by 10
  bool friction_lag = true;  // one more iteration
  // Soft objects meshed uniformly (no interior growth) at the same surface edge; not by
  // default: it asks whether the mesh, not the numerics, sets a verdict.
  bool mesh = false;
  // The fin-ray finger meshed finer (kFineFinRayLayers, kFineFinRayEdge); not by default: it
  // asks whether the finger's mesh sets a verdict. Production models only.
  bool finger = false;

  bool any() const { return dt || newton_tol || friction_lag || mesh || finger; }
};

// A gripper and an object model: one column of the benchmark.
struct LabelsArm {
  std::string gripper;  // registry name
  bool soft = false;
};

// "fin-ray:soft" -> {"fin-ray", true}. Throws std::invalid_argument without the object model;
// the message leaves naming the command to its caller.
LabelsArm parse_labels_arm(const std::string& text);

// "fin-ray x soft".
std::string labels_arm_name(const LabelsArm& arm);

struct LabelsOptions {
  // Empty: parallel-jaw x rigid, fin-ray x rigid, fin-ray x soft, leap x rigid.
  std::vector<LabelsArm> arms;
  std::vector<std::string> categories;  // empty: kLabelsCategories; {"all"}: the library's
  int seeds = 2;                        // shapes per category
  int candidates = 4;                   // per shape
  int threads = 0;                      // 0: all cores
  bool production_models = false;       // RobustnessOptions::production_models
  double soft_interior_growth = geometry::kSoftObjectInteriorGrowth;  // RobustnessOptions's
  trial::TrialParameters defaults;  // the protocol's defaults unless a bench option says
  LabelsRefinement refinement;
  bool full_trials = false;  // RobustnessOptions::full_trials, at the defaults and the reference
  std::filesystem::path out = "out/labels";
};

// The default categories: four that every gripper finds candidates on.
inline const std::vector<std::string> kLabelsCategories = {"box", "cylinder", "capsule", "bottle"};

// The categories the options ask for: kLabelsCategories when none, every category of the object
// library for {"all"}.
std::vector<std::string> labels_categories(const LabelsOptions& options);

// The reference settings for `defaults`: dt / dt_divisor (2), newton_tol / 10, one more friction
// lag iteration (those `refinement` asks for). What the protocol measures in seconds and metres
// stays the same: at dt / k its steps are counted at the reference's dt (settle_steps and
// settle_max_steps times k), and the verdict's displacement threshold stays the same length
// (displacement_factor times k): a verdict is "moved less than 1 mm", not a multiple of the step.
trial::TrialParameters reference_parameters(const trial::TrialParameters& defaults,
                                            const LabelsRefinement& refinement = {});

// One arm's trials, run at the defaults and at the reference, in the same order.
struct LabelsArmResult {
  LabelsArm arm;
  RobustnessResult defaults;
  RobustnessResult reference;  // empty when the refinement refines nothing
};

struct LabelsResult {
  std::vector<LabelsArmResult> arms;
  trial::TrialParameters defaults;
  trial::TrialParameters reference;
  LabelsRefinement refinement;  // how the reference differs from the defaults
  int threads = 0;
  double wall_seconds = 0.0;
};

// Throws std::invalid_argument for an unknown gripper or category, or seeds or candidates
// below 1.
void check_labels_options(const LabelsOptions& options);

LabelsResult run_labels(const LabelsOptions& options);

}  // namespace grip::bench
