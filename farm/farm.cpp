#include "farm/farm.hpp"

#include <sched.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <thread>

#include "farm/live_progress.hpp"
#include "farm/petsc_groups.hpp"
#include "farm/plan.hpp"
#include "farm/stop_request.hpp"
#include "farm/wire.hpp"
#include "farm/work_unit_claims.hpp"
#include "io/dataset_error.hpp"
#include "io/dataset_writer.hpp"
#include "src/config/config.hpp"
#include "src/grippers/gripper_registry.hpp"
#include "src/trial/trial.hpp"

namespace grip::farm {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Rank 0 reads the job file; every rank parses that same text, so all agree on the job and
// fail alike on a bad one.
Job read_job(const std::filesystem::path& file, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string text, error;
  if (rank == 0) {
    try {
      text = read_job_text(file);
    } catch (const config::ConfigError& e) {
      error = e.what();
    }
  }
  broadcast(error, 0, comm);
  if (!error.empty()) throw config::ConfigError(error);
  broadcast(text, 0, comm);
  return parse_job(std::move(text), file);
}

// The cores this process may run on: mpirun binds each rank to one core by default.
int usable_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// Ranks on this node share its cores, and each keeps to the cores it is bound to.
int default_threads(MPI_Comm comm) {
  MPI_Comm node;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int local_ranks = 1;
  MPI_Comm_size(node, &local_ranks);
  MPI_Comm_free(&node);
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, std::min(usable_cores(), cores / local_ranks));
}

// What a rank claims and runs as one solver::Batch: candidates of one object and gripper.
struct WorkUnit {
  std::uint32_t object = 0;
  std::uint32_t gripper = 0;
  std::vector<std::uint64_t> ids;
};

// Pending candidates in id order, cut into work units of at most `size` candidates.
std::vector<WorkUnit> make_work_units(const io::DatasetPlan& plan,
                                      const std::vector<std::uint64_t>& pending, int size) {
  std::vector<WorkUnit> units;
  for (std::uint64_t id : pending) {
    const io::CandidateSlot& slot = plan.candidates[id];
    if (units.empty() || units.back().object != slot.object ||
        units.back().gripper != slot.gripper || static_cast<int>(units.back().ids.size()) == size) {
      units.push_back({slot.object, slot.gripper, {}});
    }
    units.back().ids.push_back(id);
  }
  return units;
}

// The trial scenes this rank has built, by (object, gripper setting); consecutive work units
// mostly share one, so only the most recent few are kept.
class SceneCache {
 public:
  SceneCache(const FarmPlan& plan, const Job& job) : plan_(plan), job_(job) {}

  const trial::TrialScene& get(std::uint32_t object, std::uint32_t gripper) {
    const auto key = std::make_pair(object, gripper);
    for (auto& [k, scene] : scenes_) {
      if (k == key) return *scene;
    }
    if (scenes_.size() == kKept) scenes_.erase(scenes_.begin());
    const GripperSetting& setting = job_.grippers[gripper];
    scenes_.emplace_back(
        key, trial::make_trial_scene(trial_object(plan_.dataset.objects[object]), setting.type,
                                     setting.bimanual ? 2 : 1, job_.trial));
    return *scenes_.back().second;
  }

 private:
  static constexpr std::size_t kKept = 2;
  const FarmPlan& plan_;
  const Job& job_;
  std::vector<
      std::pair<std::pair<std::uint32_t, std::uint32_t>, std::unique_ptr<trial::TrialScene>>>
      scenes_;
};

// Rank 0 checks the dataset to resume; its refusal is every rank's.
void check_dataset(const FarmOptions& options, const std::filesystem::path& dataset,
                   MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  if (rank == 0 && options.check_dataset && std::filesystem::exists(dataset)) {
    try {
      options.check_dataset(dataset);
    } catch (const io::DatasetError& e) {
      error = e.what();
    }
  }
  broadcast(error, 0, comm);
  if (!error.empty()) throw io::DatasetError(error);
}

// What failed, for the message: the rank, the candidates and their object and gripper.
std::string trial_failure(int rank, const WorkUnit& unit, const FarmPlan& plan, const Job& job,
                          const char* what) {
  return "rank " + std::to_string(rank) + ": the trials of candidates " +
         std::to_string(unit.ids.front()) + " to " + std::to_string(unit.ids.back()) + " (" +
         plan.dataset.objects[unit.object].name + " with " + job.grippers[unit.gripper].type.name +
         (job.grippers[unit.gripper].bimanual ? ", bimanual" : "") + ") failed: " + what +
         "; the results committed so far are kept (grip farm --resume continues)";
}

// The run's settings: the dataset, ranks, threads per rank and work unit size.
FarmReport start_report(const FarmOptions& options, const Job& job, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  FarmReport report;
  report.dataset = options.output.empty() ? job.output : options.output;
  MPI_Comm_size(comm, &report.ranks);
  report.threads = options.threads > 0 ? options.threads : default_threads(comm);
  if (report.threads > usable_cores()) {
    spdlog::warn(
        "rank {} runs {} threads but may use {} core(s); under mpirun pass --bind-to none "
        "(or --map-by slot:PE={}) so its threads get cores of their own",
        rank, report.threads, usable_cores(), report.threads);
  }
  // The work unit size may differ between runs: results do not depend on it.
  report.work_unit_size = options.work_unit_size > 0 ? options.work_unit_size
                          : job.work_unit_size > 0   ? job.work_unit_size
                                                     : 4 * report.threads;
  return report;
}

io::Provenance provenance_of(const FarmOptions& options, const Job& job) {
  io::Provenance provenance;
  provenance.job_file = options.job.string();
  provenance.job_text = job.text;
  provenance.seed = job.seed;
  provenance.grip_version = options.grip_version;
  provenance.git_revision = options.git_revision;
  provenance.parameters = resolved_parameters(job);
  return provenance;
}

// Refuses before the (long) planning what the writer would refuse after it, and reopens the
// dataset to resume. (grip farm checks --output on its command line; the job's own output is
// known only here.)
std::optional<io::DatasetWriter> reopen_to_resume(const FarmOptions& options,
                                                  const std::filesystem::path& dataset,
                                                  const io::Provenance& provenance, MPI_Comm comm) {
  if (std::filesystem::is_directory(dataset)) {
    throw config::ConfigError(options.job.string() + ": the dataset '" + dataset.string() +
                              "' is a directory; give a file path (--output or [job] output)");
  }
  if (!options.resume && std::filesystem::exists(dataset)) {
    throw io::DatasetError(dataset.string() +
                           ": the dataset already exists; continue it with --resume, or choose "
                           "another output (--output or the job's [job] output)");
  }
  if (!options.resume) return std::nullopt;
  check_dataset(options, dataset, comm);
  io::DatasetWriter writer = io::DatasetWriter::resume(dataset, provenance, comm);
  if (!writer.damaged().empty()) {  // rank 0 only
    const io::Damage& first = writer.damaged().front();
    spdlog::warn(
        "{}: {} committed rows do not match their checksums; their candidates are redone "
        "(first: candidate {}, {})",
        dataset.string(), writer.damaged().size(), first.candidate, first.dataset);
  }
  return writer;
}

FarmPlan plan_job(const FarmOptions& options, const Job& job, FarmReport& report,
                  LiveProgress& progress, MPI_Comm comm) {
  const Clock::time_point plan_start = Clock::now();
  FarmPlan plan = make_plan(job, comm, report.threads, progress);
  report.plan_seconds = seconds_since(plan_start);
  if (plan.candidates.empty()) {  // every rank has the same plan, so all fail alike
    throw config::ConfigError(options.job.string() +
                              ": no candidate was synthesized for any object; the objects may not "
                              "fit the grippers ([randomization] scale, [[objects]])");
  }
  return plan;
}

// The resumed dataset's writer, checked against the plan, or a new dataset's.
io::DatasetWriter writer_for(std::optional<io::DatasetWriter> resumed, const FarmPlan& plan,
                             const std::filesystem::path& dataset, const io::Provenance& provenance,
                             MPI_Comm comm) {
  if (resumed) {
    resumed->check_plan(plan.dataset);
    return std::move(*resumed);
  }
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0 && dataset.has_parent_path()) {
    std::filesystem::create_directories(dataset.parent_path());
  }
  MPI_Barrier(comm);
  return io::DatasetWriter::create(dataset, plan.dataset, provenance, comm);
}

// Where a rank's trial phase goes: claiming, running and committing work units.
struct UnitRun {
  const FarmPlan& plan;
  const Job& job;
  int threads = 1;
  SceneCache& scenes;
  LiveProgress& progress;
  io::DatasetWriter& writer;
  MPI_Comm comm;
  // A PETSc group's leader: its group's solver, for its group-only units.
  std::shared_ptr<solver::LinearSystemSolver> big_system_solver;
};

// The dataset keeps a failure's kind; where the solver gave up (or the grasp never settled), its
// own words go to the log with the candidate, for whoever takes up the hard case: the same
// reason `grip trial --report` gives.
void log_solver_failure(const trial::TrialOutcome& outcome, const WorkUnit& unit,
                        const UnitRun& run) {
  const io::FailureKind failure = outcome.result.record.failure;
  if (outcome.failure_reason.empty() ||
      (failure != io::FailureKind::kNewtonLimit && failure != io::FailureKind::kNumerical &&
       failure != io::FailureKind::kUnsettled)) {
    return;
  }
  spdlog::warn("candidate {} ({} with {}): {}: {}", outcome.result.record.id,
               run.plan.dataset.objects[unit.object].name, run.job.grippers[unit.gripper].type.name,
               io::to_string(failure), outcome.failure_reason);
}

// One work unit's trials, its results as the dataset keeps them; each solver step adds the
// trials that ended to the progress, and rank 0 polls the progress and the journal. A
// group-only unit's systems all go to the leader's group.
std::vector<io::CandidateResult> run_unit(const WorkUnit& unit, bool group_only,
                                          const UnitRun& run) {
  std::vector<synth::Candidate> candidates;
  for (std::uint64_t id : unit.ids) candidates.push_back(run.plan.candidates[id]);
  std::size_t counted = 0;  // of this work unit's trials, added to the progress
  trial::TrialRunOptions options;
  options.threads = run.threads;
  options.trajectory = run.plan.dataset.candidates[unit.ids.front()].frames;
  options.ids = unit.ids;
  options.max_active = 2 * run.threads;  // enough to keep every thread busy while others freeze
  options.full_trials = run.job.full_trials;
  options.after_step = [&](std::size_t ended) {
    run.progress.add(LiveProgress::kTrials, ended - counted);
    counted = ended;
    run.progress.poll();
    run.writer.poll_journal();
  };
  if (group_only) options.big_system_solver = run.big_system_solver;
  std::vector<io::CandidateResult> results;
  for (trial::TrialOutcome& outcome :
       trial::run_trials(run.scenes.get(unit.object, unit.gripper), candidates, options)) {
    io::CandidateResult& result = outcome.result;
    log_solver_failure(outcome, unit, run);
    const io::CandidateSlot& slot = run.plan.dataset.candidates[result.record.id];
    if (!slot.stress) result.stress.reset();
    if (!slot.finger_stress) result.finger_stress.reset();
    results.push_back(std::move(result));
  }
  run.progress.add(LiveProgress::kTrials, unit.ids.size() - counted);
  return results;
}

// With PETSc groups, which work units only a group's leader may claim: those whose trial model
// the job's rule sends to a group ([farm] petsc_min_factor_mib, petsc_min_dofs), so that no
// plain rank's CHOLMOD takes a system the rule says is too big for it. Rank 0 builds each
// (object, gripper) pair's model once and tells every rank; without groups, none.
std::vector<char> group_only_units(const std::vector<WorkUnit>& units, const Job& job,
                                   SceneCache& scenes, MPI_Comm comm) {
  std::vector<char> group_only(units.size(), 0);
  if (job.petsc.group_ranks == 0) return group_only;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, char> by_pair;
    std::size_t count = 0;
    for (std::size_t k = 0; k < units.size(); ++k) {
      const auto pair = std::make_pair(units[k].object, units[k].gripper);
      auto known = by_pair.find(pair);
      if (known == by_pair.end()) {
        const solver::Model& model = *scenes.get(pair.first, pair.second).model();
        known = by_pair.emplace(pair, too_big_for_one_rank(job.petsc, model)).first;
      }
      group_only[k] = known->second;
      count += known->second ? units[k].ids.size() : 0;
    }
    spdlog::info("PETSc: {} candidate(s) too big for one rank's CHOLMOD, for the groups' leaders",
                 count);
  }
  MPI_Bcast(group_only.data(), static_cast<int>(group_only.size()), MPI_CHAR, 0, comm);
  return group_only;
}

struct RankTrials {
  std::uint64_t committed = 0;  // candidates this rank committed
  std::string error;            // its failed trial's message, if one failed
};

// This rank's share: claim a work unit, run it, commit it alone, claim the next, until the
// units are handed out. Two queues: the units every rank may run (queue 0), and those only a
// PETSc group's leader may (queue 1, `group_only`), which a leader takes first. A stop request
// or a failed trial here ends the handing out for every rank, each finishing the work unit it
// runs.
RankTrials run_claimed_units(const std::vector<WorkUnit>& units,
                             const std::vector<char>& group_only, bool leader, const UnitRun& run,
                             WorkUnitClaims& claims, int rank) {
  std::array<std::vector<std::size_t>, 2> queues;
  for (std::size_t k = 0; k < units.size(); ++k) queues[group_only[k] ? 1 : 0].push_back(k);
  RankTrials mine;
  int queue = leader ? 1 : 0;
  while (!stop_requested()) {
    const std::uint64_t claimed = claims.claim(queue);
    if (claimed >= queues[queue].size()) {
      if (queue == 0 || claimed >= units.size()) break;  // handed out, or no more at all
      queue = 0;
      continue;
    }
    const std::size_t k = queues[queue][claimed];
    std::vector<io::CandidateResult> results;
    try {
      results = run_unit(units[k], queue == 1, run);
    } catch (const std::exception& e) {
      mine.error = trial_failure(rank, units[k], run.plan, run.job, e.what());
      break;
    }
    try {
      run.writer.commit_unit(results);
    } catch (const std::exception& e) {
      // The other ranks would wait for this one at the end (and its writer's collective close
      // for them): stop them all. The units committed so far are kept.
      spdlog::error(
          "rank {}: committing candidates {} to {} failed: {}; the results committed so far "
          "are kept (grip farm --resume continues)",
          rank, units[k].ids.front(), units[k].ids.back(), e.what());
      MPI_Abort(run.comm, 1);
    }
    mine.committed += results.size();
  }
  if (stop_requested() || !mine.error.empty()) claims.hand_out_no_more(units.size());
  return mine;
}

// The trial phase: every pending candidate's trial, each work unit committed by the rank that
// ran it as soon as it ends; no rank waits for another until the last unit is handed out.
void run_trials(const FarmOptions& options, const FarmPlan& plan, const Job& job,
                io::DatasetWriter& writer, LiveProgress& progress, FarmReport& report,
                MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::vector<std::uint64_t> pending = writer.pending();
  report.candidates = plan.candidates.size();
  report.done_before = report.candidates - pending.size();
  const std::vector<WorkUnit> units = make_work_units(plan.dataset, pending, report.work_unit_size);
  if (rank == 0) {
    // "batches" is the user's word for work units (--batch, [farm] batch).
    spdlog::info("{} of {} candidates pending: {} batches of up to {} on {} rank(s) x {} thread(s)",
                 pending.size(), report.candidates, units.size(), report.work_unit_size,
                 report.ranks, report.threads);
  }
  const Clock::time_point trial_start = Clock::now();
  progress.start_trials(pending.size());
  SceneCache scenes(plan, job);
  const std::vector<char> group_only = group_only_units(units, job, scenes, comm);
  WorkUnitClaims claims(comm, 2);
  PetscGroups groups(job.petsc, options.petsc_options, comm);
  UnitRun run{plan, job, report.threads, scenes, progress, writer, comm, {}};
  if (groups.leader()) {
    // One caller at a time, on this thread (MPI_THREAD_FUNNELED): the leader runs one thread.
    run.threads = 1;
    run.big_system_solver = groups.leader_solver();
  }
  if (rank == 0 && job.petsc.group_ranks > 0) {
    spdlog::info(
        "PETSc: {} group(s) of {} rank(s) (the last {} ranks; each group's first rank "
        "claims work units on one thread) solve the Newton systems of trials whose CHOLMOD "
        "factor would take {} MiB or more{}",
        job.petsc.groups, job.petsc.group_ranks, job.petsc.ranks(), job.petsc.min_factor_mib,
        job.petsc.min_dofs > 0 ? fmt::format(", or of {} DOFs or more", job.petsc.min_dofs) : "");
  }
  RankTrials mine;
  if (groups.member()) {
    groups.serve();
  } else {
    mine = run_claimed_units(units, group_only, groups.leader(), run, claims, rank);
    groups.release();
  }
  report.petsc_groups = job.petsc.group_ranks > 0 ? job.petsc.groups : 0;
  report.petsc_solves = groups.total_solves(comm);
  writer.end_units([&] { progress.poll(); });
  // A rank whose trial failed took no further work unit; now, with every commit journaled,
  // every rank learns the lowest failing rank's error, so none waits in a collective for it.
  if (const std::string failed = first_error(mine.error, comm); !failed.empty()) {
    throw TrialError(failed);
  }
  MPI_Allreduce(&mine.committed, &report.done, 1, MPI_UINT64_T, MPI_SUM, comm);
  progress.log_trials(report.done);
  report.interrupted = report.done < pending.size();
  report.trial_seconds = seconds_since(trial_start);
}

}  // namespace

FarmReport run_farm(const FarmOptions& options, MPI_Comm comm) {
  stop_at_once(true);
  install_stop_handlers();
  end_with_launcher();
  const Job job = read_job(options.job, comm);
  check_petsc_groups(job.petsc, comm);
  if (!options.petsc_options.empty() && job.petsc.group_ranks == 0) {
    throw config::ConfigError(options.job.string() +
                              ": PETSc options were given after '--', but the job has no PETSc "
                              "group to take them: set [farm] petsc_group_ranks, or drop them");
  }
  FarmReport report = start_report(options, job, comm);
  const io::Provenance provenance = provenance_of(options, job);
  std::optional<io::DatasetWriter> resumed =
      reopen_to_resume(options, report.dataset, provenance, comm);
  LiveProgress progress(comm, options.progress_interval);
  const FarmPlan plan = plan_job(options, job, report, progress, comm);
  stop_at_once(false);  // from here a stop signal lets the work units in flight commit
  io::DatasetWriter writer = writer_for(std::move(resumed), plan, report.dataset, provenance, comm);
  run_trials(options, plan, job, writer, progress, report, comm);
  writer.close();
  return report;
}

}  // namespace grip::farm
