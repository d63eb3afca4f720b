// grip trial: grasp trials of candidates from a candidate file, as one batch, with a JSON
// report, optional VTK frame series and an optional check against solo runs (docs/trial.md).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "app/cli/command_line.hpp"
#include "app/cli/device_option.hpp"
#include "app/commands/commands.hpp"
#include "app/commands/gripper_option.hpp"
#include "app/commands/parameter_options.hpp"
#include "solver/batch/engines.hpp"
#include "src/geometry/boundary_surface.hpp"
#include "src/geometry/mesh_measures.hpp"
#include "src/geometry/tetrahedralize.hpp"
#include "src/grippers/gripper_registry.hpp"
#include "src/platform/process_memory.hpp"
#include "src/scene/sim_parameters.hpp"
#include "src/synth/candidate_file.hpp"
#include "src/synth/object_spec.hpp"
#include "src/trial/same_result.hpp"
#include "src/trial/trial.hpp"
#include "src/trial/trial_report.hpp"
#include "src/trial/vtk_series.hpp"

namespace grip::commands {

namespace {

// The object and gripper come from the candidate file; given on the command line they must
// agree with it.
struct TrialArgs {
  std::optional<std::string> object;  // a category name (shape from the seed) or a mesh file
  std::optional<double> scale;        // multiplies a mesh file's coordinates
  std::optional<std::uint64_t> seed;  // the category's shape, as given to grip synth
  bool soft = false;                  // FEM object (tetrahedralized) instead of one affine body
  double tet_edge = 0.008;            // m, target tet edge length of a soft object
  double tet_growth = geometry::kSoftObjectInteriorGrowth;  // TetOptions::interior_growth
  double tets_across = objects::kDefaultTetsAcross;  // a category's thinnest part over the edge
  double max_tets = geometry::kMaxEstimatedTets;     // a finer soft object is refused
  double density = 1000.0;                           // kg/m^3
  double youngs = 1e6;                               // Pa, soft objects
  double poisson = 0.4;                              // soft objects
  double friction = 3.5;               // the object's mu (a fin-ray pad's pairs use the pad's 3.5)
  std::optional<std::string> gripper;  // a name of the gripper registry or a description file
  std::string candidates;              // candidate file (docs/synthesis.md)
  bool bimanual = false;               // the file's candidates are bimanual (two grippers)
  std::string index = "0";             // one candidate "I" or a range "A-B", run as one batch
  std::string report;                  // JSON report file; stdout when empty
  std::string vtk;                     // folder for per-candidate VTK series; none when empty
  int threads = 0;                     // 0: all cores
  std::string device = "cpu";          // the engine: cpu, host (data-parallel) or cuda
  bool compare_solo = false;           // also run each candidate alone: speedup and identity
  bool full_trials = false;            // run decided trials to the end (TrialRunOptions)
  trial::TrialParameters parameters;   // the protocol's and the solver's (their tables' options)
  // The fin-ray finger's mesh (grippers::FinRayOptions layers and edge_length); unset: its
  // defaults. Refused for other grippers.
  std::optional<int> finger_layers;
  std::optional<double> finger_edge;  // m
};

// "I" or "A-B" (inclusive) into candidate indices below `count`.
std::vector<std::size_t> parse_indices(const std::string& text, std::size_t count) {
  std::size_t first = 0, last = 0;
  char dash = 0;
  std::istringstream in(text);
  bool ok = static_cast<bool>(in >> first);
  if (ok && in >> dash)
    ok = dash == '-' && static_cast<bool>(in >> last) && (in >> std::ws).eof();
  else
    last = first;
  if (!ok || text.find_first_not_of("0123456789-") != std::string::npos || last < first) {
    throw std::invalid_argument("--index '" + text + "': expected I or A-B (e.g. 0-63)");
  }
  if (last >= count) {
    throw std::invalid_argument("--index " + text + ": the candidate file has " +
                                std::to_string(count) + " candidates (0-" +
                                std::to_string(count - 1) + ")");
  }
  std::vector<std::size_t> indices;
  for (std::size_t i = first; i <= last; ++i) indices.push_back(i);
  return indices;
}

// The fin-ray finger as --finger-layers and --finger-edge mesh it.
grippers::FinRayOptions fin_ray_options(const TrialArgs& args) {
  grippers::FinRayOptions options;
  if (args.finger_layers) options.layers = *args.finger_layers;
  if (args.finger_edge) options.edge_length = *args.finger_edge;
  return options;
}

// Each candidate run again alone, on one thread: the batch's speedup, memory, and whether each
// solo run is the batch's bit for bit (into the report).
void compare_solo(const trial::TrialScene& scene, const std::vector<synth::Candidate>& candidates,
                  const trial::TrialRunOptions& options,
                  const std::vector<trial::TrialOutcome>& outcomes, double seconds,
                  trial::TrialReport& report) {
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    trial::TrialRunOptions solo = options;
    solo.threads = 1;
    solo.ids = {options.ids[k]};
    solo.body_frames = false;
    const platform::MemoryPeak solo_memory;
    const auto solo_start = std::chrono::steady_clock::now();
    const trial::TrialOutcome alone = trial::run_trials(scene, {candidates[k]}, solo).front();
    report.solo_wall_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - solo_start).count();
    report.solo_memory_mib = std::max(report.solo_memory_mib, solo_memory.mib());
    if (!trial::same_result(alone.result, outcomes[k].result)) {
      report.identical_to_solo = false;
      spdlog::error("candidate {}: the solo run differs from the batch", options.ids[k]);
    }
  }
  spdlog::info("solo runs: {:.3f} s; batch speedup {:.2f}; identical: {}", report.solo_wall_seconds,
               report.solo_wall_seconds / seconds, report.identical_to_solo);
  spdlog::info("peak memory: the batch {:.1f} MiB, one candidate alone {:.1f} MiB{}",
               report.batch_memory_mib, report.solo_memory_mib,
               candidates.size() > 1
                   ? fmt::format(", {:.2f} MiB per added environment",
                                 report.memory_per_added_environment_mib(candidates.size()))
                   : std::string());
}

// Runs the candidates as one batch, optionally one by one too, writes the VTK series and the
// report; 1 when a solo run differs from the batch.
int run_and_report(const TrialArgs& args, const trial::TrialScene& scene,
                   const std::vector<synth::Candidate>& candidates,
                   const std::vector<std::uint64_t>& ids) {
  trial::TrialRunOptions options;
  options.threads = args.threads;
  options.device = solver::engine_device(args.device);
  options.ids = ids;
  options.body_frames = !args.vtk.empty();
  options.full_trials = args.full_trials;
  // Memory is measured only to compare with solo runs (it trims the heap first).
  std::optional<platform::MemoryPeak> batch_memory;
  if (args.compare_solo) batch_memory.emplace();
  const auto start = std::chrono::steady_clock::now();
  const std::vector<trial::TrialOutcome> outcomes = trial::run_trials(scene, candidates, options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  spdlog::info("{} trial(s) in {:.3f} s", outcomes.size(), seconds);

  trial::TrialReport report;
  report.compared_solo = args.compare_solo;
  if (args.compare_solo) {
    report.batch_memory_mib = batch_memory->mib();
    compare_solo(scene, candidates, options, outcomes, seconds, report);
  }
  if (!args.vtk.empty()) {
    for (const trial::TrialOutcome& outcome : outcomes) {
      trial::write_vtk_series(args.vtk, "candidate_" + std::to_string(outcome.result.record.id),
                              *scene.model(), outcome.body_frames);
    }
  }
  report.object = *args.object;
  report.gripper = *args.gripper;
  const grippers::GripperType* type = grippers::find_gripper_type(*args.gripper);
  if (type && type->meshed_finger) report.fin_ray = fin_ray_options(args);
  report.soft = args.soft;
  report.grippers = scene.gripper_count();
  report.threads = solver::make_engine(options.device, args.threads)->threads();
  report.device = args.device;
  report.wall_seconds = seconds;
  if (args.report.empty()) {
    trial::write_report(std::cout, report, outcomes);
  } else {
    std::ofstream out(args.report);
    if (!out) throw std::runtime_error("--report " + args.report + ": cannot write the file");
    trial::write_report(out, report, outcomes);
  }
  return report.identical_to_solo ? 0 : 1;
}

// The object and gripper the candidate file names, checked against what the command line says
// (a trial on another object than the candidates' would start every grasp inside it).
TrialArgs with_file_object(const TrialArgs& given, const synth::CandidateFile& file) {
  const synth::CandidateObject& o = file.object;
  TrialArgs args = given;
  const auto mismatch = [&](const std::string& option, const std::string& file_value,
                            const std::string& given_value) {
    throw std::invalid_argument(given.candidates + ": the candidates were synthesized with " +
                                option + " " + file_value + ", not " + given_value + "; leave " +
                                option + " out or synthesize again");
  };
  if (args.object && *args.object != o.spec) mismatch("--object", o.spec, *args.object);
  if (args.seed && *args.seed != o.seed) {
    mismatch("--seed", std::to_string(o.seed), std::to_string(*args.seed));
  }
  if (args.scale && *args.scale != o.scale) {
    mismatch("--scale", std::to_string(o.scale), std::to_string(*args.scale));
  }
  args.object = o.spec;
  args.seed = o.seed;
  args.scale = o.scale;
  if (synth::object_file_hash(o.spec) != o.content_hash) {
    throw std::invalid_argument(given.candidates + ": the mesh file '" + o.spec +
                                "' changed since the candidates were synthesized on it; "
                                "synthesize again");
  }
  // A described gripper is known by its file, which the command line must give.
  if (!args.gripper && !grippers::find_gripper_type(file.gripper)) {
    throw std::invalid_argument(given.candidates +
                                ": the candidates were synthesized with the "
                                "described gripper '" +
                                file.gripper + "'; pass --gripper with its description file");
  }
  if (!args.gripper) args.gripper = file.gripper;
  return args;
}

// The gripper --gripper names, which must be the candidate file's.
grippers::GripperType file_gripper(const TrialArgs& args, const synth::CandidateFile& file) {
  grippers::GripperType type = grippers::resolve_gripper(*args.gripper);
  if (type.name != file.gripper) {
    throw std::invalid_argument(args.candidates +
                                ": the candidates were synthesized with "
                                "--gripper " +
                                file.gripper + ", not " + type.name + " (" + *args.gripper +
                                "); leave --gripper out or synthesize again");
  }
  return type;
}

// The candidates --index names, checked against the gripper and --bimanual (their record ids
// into `ids`).
std::vector<synth::Candidate> chosen_candidates(const TrialArgs& args,
                                                const synth::CandidateFile& file,
                                                const grippers::GripperType& type,
                                                std::vector<std::uint64_t>& ids) {
  const std::vector<synth::Candidate>& candidates = file.candidates;
  // A candidate file holds one kind of candidate (write_candidates refuses a mix): the first
  // says whether the file is bimanual.
  const bool file_bimanual = candidates.front().hands.size() == 2;
  if (file_bimanual && !args.bimanual) {
    throw std::invalid_argument(args.candidates +
                                ": the candidates are bimanual (two grippers each); pass "
                                "--bimanual to run them, or give a unimanual candidate file");
  }
  if (!file_bimanual && args.bimanual) {
    throw std::invalid_argument(args.candidates +
                                ": the candidates are unimanual (one gripper each), not bimanual; "
                                "leave --bimanual out or synthesize with grip synth --bimanual");
  }
  const std::size_t hands = args.bimanual ? 2 : 1;
  std::vector<synth::Candidate> chosen;
  for (std::size_t i : parse_indices(args.index, candidates.size())) {
    const synth::Candidate& c = candidates[i];
    const bool joints_fit = std::all_of(c.hands.begin(), c.hands.end(), [&](const auto& hand) {
      return hand.joints.size() == type.joints;
    });
    if (c.gripper != type.kind || c.hands.size() != hands || !joints_fit) {
      throw std::invalid_argument(args.candidates + ": candidate " + std::to_string(i) +
                                  " is for '" + file.gripper + "' with " +
                                  std::to_string(c.hands.size()) + " hand(s), not " +
                                  (hands == 1 ? "one" : "two") + " '" + *args.gripper +
                                  "'; synthesize with the same --gripper");
    }
    chosen.push_back(c);
    ids.push_back(i);
  }
  return chosen;
}

// The object as the command line says: the candidate file's shape, rigid or tetrahedralized.
trial::TrialObject trial_object(const TrialArgs& args) {
  trial::TrialObject object;
  object.name = *args.object;
  object.surface = synth::load_object(*args.object, *args.seed, *args.scale);
  object.material = {args.density, args.youngs, args.poisson, args.friction};
  if (!args.soft) return object;
  geometry::TetOptions options;
  options.edge_length =
      synth::object_tet_edge(*args.object, *args.seed, 1.0, args.tet_edge, args.tets_across);
  options.interior_growth = args.tet_growth;
  if (options.edge_length < args.tet_edge) {
    spdlog::info("tet edge {:.4f} m: the object's thinnest part over {:g}", options.edge_length,
                 args.tets_across);
  }
  const double tets = geometry::estimated_tet_count(
      std::abs(geometry::surface_volume(object.surface)), options.edge_length);
  if (tets > args.max_tets) {
    throw std::invalid_argument(
        fmt::format("--tet-edge: a tet edge of {:g} m would make about {:.3g} tets for '{}', "
                    "more than the {:.0f} allowed; use a larger --tet-edge (or raise "
                    "--max-tets)",
                    options.edge_length, tets, *args.object, args.max_tets));
  }
  object.tets = geometry::tetrahedralize(object.surface, options, *args.object);
  object.surface = geometry::boundary_surface(*object.tets);
  spdlog::info("soft object: {} vertices, {} tets", object.tets->vertices.rows(),
               object.tets->tets.rows());
  return object;
}

int trial(const TrialArgs& given) {
  const synth::CandidateFile file = synth::read_candidates(given.candidates);
  if (file.candidates.empty()) throw std::invalid_argument(given.candidates + ": no candidates");
  const TrialArgs args = with_file_object(given, file);
  const grippers::GripperType type = file_gripper(args, file);
  if ((args.finger_layers || args.finger_edge) && !type.meshed_finger) {
    throw std::invalid_argument(
        std::string(args.finger_layers ? "--finger-layers" : "--finger-edge") +
        ": only the fin-ray gripper has a meshed finger, not '" + *args.gripper +
        "'; leave it out");
  }
  std::vector<std::uint64_t> ids;
  const std::vector<synth::Candidate> candidates = chosen_candidates(args, file, type, ids);
  const trial::TrialObject object = trial_object(args);
  const grippers::FinRayOptions finger = fin_ray_options(args);
  const std::unique_ptr<trial::TrialScene> scene =
      trial::make_trial_scene(object, type, args.bimanual ? 2 : 1, args.parameters, finger);
  if (type.meshed_finger) {
    spdlog::info("fin-ray finger: {} tet layers, profile edges up to {:g} m: {}", finger.layers,
                 finger.edge_length, scene->description());
  }
  return run_and_report(args, *scene, candidates, ids);
}

// The object's options: its shape (the candidate file's), and its model and material.
void declare_object_options(cli::Command& trial, TrialArgs& args) {
  trial.option("--object", args.object,
               "Object category or mesh file (default: the candidate file's; must agree)");
  trial
      .option("--seed", args.seed,
              "The seed the candidates were synthesized with (default: the file's)")
      .check(cli::Check::count());
  trial
      .option("--scale", args.scale,
              "A mesh file's scale (default: the candidate file's; must agree)")
      .check(cli::Check::positive());
  trial.flag("--soft", args.soft, "Simulate the object as FEM (tetrahedralized)");
  trial
      .option("--max-tets", args.max_tets,
              "Soft object: refuse a --tet-edge that would make more tets")
      .show_default()
      .check(cli::Check::positive());
  trial.option("--tet-edge", args.tet_edge, "Soft object: target tet edge length (m)")
      .show_default()
      .check(cli::Check::positive());
  trial
      .option("--tet-growth", args.tet_growth,
              "Soft object: how fast tets grow with depth below the surface (m per m; 0: "
              "uniform)")
      .show_default()
      .check(cli::Check::range(0.0, geometry::kMaxInteriorGrowth));
  trial
      .option("--tets-across", args.tets_across,
              "Soft object of a category: at least this many tet edges across its thinnest part "
              "(a wall)")
      .show_default()
      .check(cli::Check::range(objects::kMinTetsAcross, objects::kMaxTetsAcross));
  trial.option("--density", args.density, "Object density (kg/m^3)")
      .show_default()
      .check(cli::Check::positive());
  trial.option("--youngs", args.youngs, "Soft object: Young's modulus (Pa)")
      .show_default()
      .check(cli::Check::positive());
  trial.option("--poisson", args.poisson, "Soft object: Poisson's ratio")
      .show_default()
      .check(cli::Check::poisson_ratio());
  trial.option("--friction", args.friction, "Object friction coefficient")
      .show_default()
      .check(cli::Check::non_negative());
}

}  // namespace

void declare_trial(cli::Command& root) {
  auto args = std::make_shared<TrialArgs>();
  cli::Command trial = root.subcommand(
      "trial",
      "Grasp trials of candidates as one batch: close, settle, six-axis gravity (docs/trial.md)");
  declare_object_options(trial, *args);
  trial
      .option("--gripper", args->gripper,
              gripper_option_help() + " (default: the candidate file's; must agree)")
      .check(gripper_check());
  trial.option("--candidates", args->candidates, "Candidate file from grip synth").required();
  trial.flag("--bimanual", args->bimanual,
             "The candidates are bimanual (grip synth --bimanual): two grippers per trial");
  trial.option("--index", args->index, "Candidate I, or A-B (inclusive) as one batch")
      .show_default();
  trial.option("--report", args->report, "Write the JSON report here (default: stdout)")
      .check(cli::Check::output_file());
  trial.option("--vtk", args->vtk, "Write each candidate's frames as a VTK series here")
      .check(cli::Check::output_folder());
  trial.option("--threads", args->threads, "Threads (default: all cores)")
      .check(cli::Check::count());
  trial.option("--device", args->device, cli::device_help())
      .show_default()
      .check(cli::device_check());
  trial.flag("--compare-solo", args->compare_solo,
             "Also run each candidate alone: batch speedup and bit-identity");
  trial.flag("--full-trials", args->full_trials,
             "Run every trial through the six gravity phases, also once its verdict is decided");
  trial
      .option("--finger-layers", args->finger_layers,
              "Fin-ray: tet layers across the finger's depth (default " +
                  std::to_string(grippers::FinRayOptions{}.layers) + ")")
      .check(cli::Check::range(1, grippers::kMaxFinRayLayers));
  trial
      .option("--finger-edge", args->finger_edge,
              fmt::format(
                  "Fin-ray: largest triangle edge of the finger's profile mesh (m; default {:g})",
                  grippers::FinRayOptions{}.edge_length))
      .check(cli::Check::range(grippers::kMinFinRayEdge, grippers::kMaxFinRayEdge));
  // Every solver and protocol setting, as a job file's [physics], [trial] and [outputs] keys.
  declare_parameters(trial, scene::sim_parameter_table(), args->parameters.sim);
  declare_parameters(trial, trial::trial_parameter_table(), args->parameters);
  trial.on_check([trial, args] {
    for (const char* soft_only :
         {"--tet-edge", "--tet-growth", "--tets-across", "--youngs", "--poisson"}) {
      if (trial.given(soft_only) && !args->soft) {
        throw cli::UsageError(soft_only, "applies to soft objects only: add --soft");
      }
    }
    cli::refuse_cuda_device(args->device);
    try {
      trial::validate(args->parameters);  // values that contradict each other
    } catch (const std::invalid_argument& e) {
      throw cli::UsageError("parameters", e.what());
    }
  });
  trial.on_run([args] { return grip::commands::trial(*args); });
}

}  // namespace grip::commands
