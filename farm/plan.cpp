#include "farm/plan.hpp"

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include "farm/wire.hpp"
#include "src/config/config.hpp"
#include "src/synth/prepared_object.hpp"
#include "src/synth/synthesize.hpp"
#include "src/trial/trial.hpp"

namespace grip::farm {
namespace {

std::vector<synth::Candidate> synthesize_for(const Job& job, const FarmObject& object,
                                             const io::ObjectRecord& record,
                                             const GripperSetting& gripper, std::uint64_t stream) {
  const synth::PreparedObject prepared(trial_object(record).surface);
  const synth::SynthesisParams params = synth::synthesis_params(job.synthesis, job.trial.sim.d_hat);
  synth::SynthesisResult result = synth::synthesize(
      prepared, gripper.type, gripper.bimanual, params, object.seed ^ stream, gripper.candidates);
  if (static_cast<int>(result.candidates.size()) < gripper.candidates) {
    spdlog::warn(
        "{} x {}{}: {} of {} candidates after {} attempts (the object may not fit the "
        "gripper)",
        object.name, gripper.type.name, gripper.bimanual ? " (bimanual)" : "",
        result.candidates.size(), gripper.candidates, result.attempts);
  }
  return std::move(result.candidates);
}

// A rank whose own share failed must not leave the others waiting in the broadcasts that
// follow: every rank learns the lowest failing rank's error and throws it, so all stop alike.
void throw_if_any_failed(const std::string& error, MPI_Comm comm) {
  const std::string shared = first_error(error, comm);
  if (!shared.empty()) throw config::ConfigError(shared);
}

}  // namespace

FarmPlan make_plan(const Job& job, MPI_Comm comm, int threads, LiveProgress& progress) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  tbb::task_arena arena(threads);

  FarmPlan plan;
  plan.objects = list_objects(job);
  const std::size_t objects = plan.objects.size();
  const std::size_t grippers = job.grippers.size();
  progress.start_plan(objects, objects * grippers);

  // Objects: prepared where they are owned, then every rank gets every record.
  std::vector<std::string> packed(objects);
  std::string error;
  for (std::size_t i = 0; i < objects && error.empty(); ++i) {
    if (static_cast<int>(i % size) != rank) continue;
    try {
      arena.execute([&] { packed[i] = pack(prepare_object(plan.objects[i])); });
      progress.add(LiveProgress::kObjects);
      progress.poll();
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  progress.wait_for_ranks();
  throw_if_any_failed(error, comm);
  for (std::size_t i = 0; i < objects; ++i) {
    broadcast(packed[i], static_cast<int>(i % size), comm);
    plan.dataset.objects.push_back(unpack_object(packed[i]));
  }

  // Candidates of each (object, gripper), the same way.
  std::vector<std::string> synthesized(objects * grippers);
  for (std::size_t u = 0; u < synthesized.size() && error.empty(); ++u) {
    if (static_cast<int>(u % size) != rank) continue;
    const std::size_t i = u / grippers, g = u % grippers;
    try {
      std::vector<synth::Candidate> candidates;
      arena.execute([&] {
        candidates =
            synthesize_for(job, plan.objects[i], plan.dataset.objects[i], job.grippers[g], g + 1);
      });
      synthesized[u] = pack(candidates);
      progress.add(LiveProgress::kPairs);
      progress.add(LiveProgress::kCandidates, candidates.size());
      progress.poll();
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  progress.wait_for_ranks();
  throw_if_any_failed(error, comm);
  for (std::size_t u = 0; u < synthesized.size(); ++u) {
    broadcast(synthesized[u], static_cast<int>(u % size), comm);
    const std::size_t i = u / grippers, g = u % grippers;
    for (synth::Candidate& c : unpack_candidates(synthesized[u])) {
      plan.dataset.candidates.push_back({static_cast<std::uint32_t>(i),
                                         static_cast<std::uint32_t>(g), job.record_frames,
                                         job.record_stress && plan.dataset.objects[i].soft});
      plan.candidates.push_back(std::move(c));
    }
  }

  // Gripper records come from a trial scene; every rank builds them the same way (the first
  // object's scene: a gripper's record does not depend on the object).
  const trial::TrialObject first = trial_object(plan.dataset.objects.front());
  for (const GripperSetting& gripper : job.grippers) {
    io::GripperRecord record =
        trial::make_trial_scene(first, gripper.type, gripper.bimanual ? 2 : 1, job.trial)
            ->gripper_record();
    plan.dataset.grippers.push_back(std::move(record));
  }
  for (io::CandidateSlot& slot : plan.dataset.candidates) {
    slot.finger_stress = job.record_stress && !plan.dataset.grippers[slot.gripper].tets.empty();
  }
  plan.dataset.closing_frames = static_cast<std::uint32_t>(job.trial.closing_frames);
  plan.dataset.validation_frames = static_cast<std::uint32_t>(job.trial.validation_frames);
  progress.log_plan();
  if (rank == 0) {
    for (std::size_t i = 0; i < objects; ++i) {
      const io::ObjectRecord& r = plan.dataset.objects[i];
      spdlog::info("object {} ({}, {}): {} vertices{}, scale {:.3f}, mu {:.2f}", r.name, r.category,
                   r.soft ? "soft" : "rigid", r.vertex_count(),
                   r.soft ? fmt::format(", {} tets", r.tet_count()) : std::string(), r.scale,
                   r.material.friction);
    }
    spdlog::info("{} candidates over {} objects and {} gripper(s)", plan.candidates.size(), objects,
                 grippers);
  }
  return plan;
}

}  // namespace grip::farm
