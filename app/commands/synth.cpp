// grip synth: candidate grasps for one object and gripper, written to a candidate file
// (docs/synthesis.md), with the attempt statistics the synthesis figures are built from.
#include <spdlog/spdlog.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>

#include "app/cli/command_line.hpp"
#include "app/commands/commands.hpp"
#include "app/commands/gripper_option.hpp"
#include "app/commands/parameter_options.hpp"
#include "src/grippers/gripper_registry.hpp"
#include "src/scene/sim_parameters.hpp"
#include "src/synth/candidate_file.hpp"
#include "src/synth/object_spec.hpp"
#include "src/synth/synthesis_settings.hpp"
#include "src/synth/synthesize.hpp"

namespace grip::commands {
namespace {

struct SynthArgs {
  std::string object;   // an object category name or a surface mesh file
  double scale = 1.0;   // multiplies a mesh file's coordinates
  std::string gripper;  // a name of the gripper registry or a description file
  bool bimanual = false;
  int count = 0;
  std::uint64_t seed = 0;
  std::string out;                    // candidate file (docs/synthesis.md)
  synth::SynthesisSettings settings;  // steps, margin
  solver::SimParameters physics;      // its d_hat: the clearance candidates keep
};

int synth(const SynthArgs& args) {
  if (args.count < 1) throw std::invalid_argument("--count must be at least 1");
  const std::filesystem::path folder = std::filesystem::path(args.out).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder)) {
    throw std::invalid_argument("--out: the folder '" + folder.string() +
                                "' does not exist; create it first");
  }
  const grippers::GripperType gripper = grippers::resolve_gripper(args.gripper);
  const synth::PreparedObject object(synth::load_object(args.object, args.seed, args.scale));
  spdlog::info("object '{}': {} vertices, {} triangles", args.object,
               object.surface().vertices.rows(), object.surface().triangles.rows());

  const synth::SynthesisParams params = synth::synthesis_params(args.settings, args.physics.d_hat);
  const synth::SynthesisResult result =
      synth::synthesize(object, gripper, args.bimanual, params, args.seed, args.count);
  const std::string file_hash = synth::object_file_hash(args.object);  // empty: a category
  const synth::CandidateObject source{args.object, args.seed, args.scale, file_hash};
  synth::write_candidates(args.out, source, gripper, result.candidates);

  for (const auto& [reason, n] : result.rejections) {
    spdlog::info("rejected {}: {}", n, reason);
  }
  std::printf(
      "%s %s%s: %zu candidates in %.3f s (%.2f candidates/s); %lld attempts, accepted "
      "fraction %.3f; wrote %s\n",
      args.object.c_str(), args.gripper.c_str(), args.bimanual ? " bimanual" : "",
      result.candidates.size(), result.seconds,
      static_cast<double>(result.candidates.size()) / result.seconds,
      static_cast<long long>(result.attempts), result.accepted_fraction(), args.out.c_str());
  if (static_cast<int>(result.candidates.size()) < args.count) {
    // The usual cause with a mesh file is its unit: grippers hold objects of a few centimetres.
    // A category's shape is drawn from the seed: another seed draws another size.
    const auto& v = object.surface().vertices;
    const Eigen::Vector3d size = (v.colwise().maxCoeff() - v.colwise().minCoeff()).transpose();
    const bool category = file_hash.empty();
    const std::string drawn = category
                                  ? fmt::format("m, the {} of --seed {}", args.object, args.seed)
                                  : fmt::format("m at --scale {:g}", args.scale);
    const std::string fix = category ? "another --seed draws another size"
                                     : "a mesh in centimetres or millimetres needs --scale 0.01 "
                                       "or 0.001";
    spdlog::warn(
        "only {} of {} candidates after {} attempts: the object ({:.3g} x {:.3g} x {:.3g} {}) "
        "may not fit the gripper; {}",
        result.candidates.size(), args.count, result.attempts, size.x(), size.y(), size.z(), drawn,
        fix);
    return 1;
  }
  return 0;
}

}  // namespace

void declare_synth(cli::Command& root) {
  auto args = std::make_shared<SynthArgs>();
  cli::Command synth = root.subcommand(
      "synth", "Synthesize candidate grasps for one object and gripper (docs/synthesis.md)");
  synth
      .option("--object", args->object,
              "Object category name (shape drawn from --seed) or surface mesh file")
      .required();
  synth.option("--scale", args->scale, "Multiply a mesh file's coordinates by this")
      .show_default()
      .check(cli::Check::positive());
  synth.option("--gripper", args->gripper, gripper_option_help()).required().check(gripper_check());
  synth.flag("--bimanual", args->bimanual, "Two hands: compose right and left candidates");
  synth.option("--count", args->count, "Number of candidates")
      .required()
      .check(cli::Check::whole_number(1, grip::synth::kMaxCandidates));
  synth.option("--seed", args->seed, "Random seed").required().check(cli::Check::count());
  synth.option("--out", args->out, "Candidate file to write")
      .required()
      .check(cli::Check::output_file());
  // [synthesis] steps and margin, and [physics] d_hat, as a job file gives them.
  declare_parameters(synth, grip::synth::synthesis_parameter_table(), args->settings);
  for (const auto& row : scene::sim_parameter_table()) {
    if (row.key == "d_hat") declare_parameters(synth, std::span(&row, 1), args->physics);
  }
  synth.on_run([args] { return grip::commands::synth(*args); });
}

}  // namespace grip::commands
