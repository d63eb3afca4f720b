#include "farm/farm.hpp"

#include <sched.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <thread>

#include "farm/live_progress.hpp"
#include "farm/plan.hpp"
#include "farm/stop_request.hpp"
#include "farm/trial_runner.hpp"
#include "farm/wire.hpp"
#include "farm/work_unit_claims.hpp"
#include "io/dataset_error.hpp"
#include "io/dataset_writer.hpp"
#include "src/config/config.hpp"
#include "src/grippers/gripper_registry.hpp"

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

// The trial scenes this rank has built, by (object, gripper); consecutive work units mostly
// share one, so only the most recent few are kept.
class RunnerCache {
 public:
  RunnerCache(const FarmPlan& plan, const Job& job) : plan_(plan), job_(job) {}

  const TrialRunner& get(std::uint32_t object, std::uint32_t gripper) {
    const auto key = std::make_pair(object, gripper);
    for (auto& [k, runner] : runners_) {
      if (k == key) return *runner;
    }
    if (runners_.size() == kKept) runners_.erase(runners_.begin());
    runners_.emplace_back(key,
                          std::make_unique<TrialRunner>(trial_object(plan_.dataset.objects[object]),
                                                        job_.grippers[gripper].kind, job_.trial));
    return *runners_.back().second;
  }

 private:
  static constexpr std::size_t kKept = 2;
  const FarmPlan& plan_;
  const Job& job_;
  std::vector<std::pair<std::pair<std::uint32_t, std::uint32_t>, std::unique_ptr<TrialRunner>>>
      runners_;
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
         plan.dataset.objects[unit.object].name + " with " +
         std::string(grippers::gripper_type(job.grippers[unit.gripper].kind).name) +
         ") failed: " + what +
         "; the results committed so far are kept (grip farm --resume continues)";
}

}  // namespace

FarmReport run_farm(const FarmOptions& options, MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  install_stop_handlers();

  const Job job = read_job(options.job, comm);
  FarmReport report;
  report.dataset = options.output.empty() ? job.output : options.output;
  report.ranks = ranks;
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

  io::Provenance provenance;
  provenance.job_file = options.job.string();
  provenance.job_text = job.text;
  provenance.seed = job.seed;
  provenance.grip_version = options.grip_version;
  provenance.git_revision = options.git_revision;
  provenance.parameters = resolved_parameters(job);

  // Refuse before the (long) planning what the writer would refuse after it. (grip farm checks
  // --output on its command line; the job's own output is known only here.)
  if (std::filesystem::is_directory(report.dataset)) {
    throw config::ConfigError(options.job.string() + ": the dataset '" + report.dataset.string() +
                              "' is a directory; give a file path (--output or [job] output)");
  }
  if (!options.resume && std::filesystem::exists(report.dataset)) {
    throw io::DatasetError(report.dataset.string() +
                           ": the dataset already exists; continue it with --resume, or choose "
                           "another output (--output or the job's [job] output)");
  }
  std::optional<io::DatasetWriter> writer;
  if (options.resume) {
    check_dataset(options, report.dataset, comm);
    writer = io::DatasetWriter::resume(report.dataset, provenance, comm);
  }
  if (writer && !writer->damaged().empty()) {  // rank 0 only
    const io::Damage& first = writer->damaged().front();
    spdlog::warn(
        "{}: {} committed rows do not match their checksums; their candidates are redone "
        "(first: candidate {}, {})",
        report.dataset.string(), writer->damaged().size(), first.candidate, first.dataset);
  }

  LiveProgress progress(comm, options.progress_interval);
  const Clock::time_point plan_start = Clock::now();
  const FarmPlan plan = make_plan(job, comm, report.threads, progress);
  report.plan_seconds = seconds_since(plan_start);
  if (plan.candidates.empty()) {  // every rank has the same plan, so all fail alike
    throw config::ConfigError(options.job.string() +
                              ": no candidate was synthesized for any object; the objects may not "
                              "fit the grippers ([randomization] scale, [[objects]])");
  }
  if (writer) {
    if (writer->layout().candidate_count != plan.candidates.size()) {
      throw io::DatasetError(report.dataset.string() +
                             ": the job now plans a different number of candidates than the "
                             "dataset holds (was it made by another grip version?); start a new "
                             "dataset instead of resuming");
    }
  } else {
    if (rank == 0 && report.dataset.has_parent_path()) {
      std::filesystem::create_directories(report.dataset.parent_path());
    }
    MPI_Barrier(comm);
    writer = io::DatasetWriter::create(report.dataset, plan.dataset, provenance, comm);
  }

  const std::vector<std::uint64_t> pending = writer->pending();
  report.candidates = plan.candidates.size();
  report.done_before = report.candidates - pending.size();
  const std::vector<WorkUnit> units = make_work_units(plan.dataset, pending, report.work_unit_size);
  // A round holds a few work units per rank, claimed as ranks go; its results are committed
  // together at its end. More work units per round balance better; fewer commit more often.
  const std::uint64_t per_round =
      static_cast<std::uint64_t>(job.round_work_units) * static_cast<std::uint64_t>(ranks);
  const std::uint64_t rounds = (units.size() + per_round - 1) / per_round;
  if (rank == 0) {
    // "batches" is the user's word for work units (--batch, [farm] batch).
    spdlog::info("{} of {} candidates pending: {} batches of up to {} on {} rank(s) x {} thread(s)",
                 pending.size(), report.candidates, units.size(), report.work_unit_size, ranks,
                 report.threads);
  }

  const Clock::time_point trial_start = Clock::now();
  progress.start_trials(pending.size());
  RunnerCache runners(plan, job);
  WorkUnitClaims claims(comm, std::max<std::uint64_t>(rounds, 1));
  for (std::uint64_t round = 0; round < rounds; ++round) {
    const std::uint64_t first = round * per_round;
    const std::uint64_t count = std::min<std::uint64_t>(per_round, units.size() - first);
    std::vector<io::CandidateResult> results;
    std::string error;
    while (error.empty() && !stop_requested()) {
      const std::uint64_t k = claims.claim(round);
      if (k >= count) break;
      const WorkUnit& unit = units[first + k];
      std::vector<const synth::Candidate*> candidates;
      for (std::uint64_t id : unit.ids) candidates.push_back(&plan.candidates[id]);
      const bool trajectory = plan.dataset.candidates[unit.ids.front()].frames;
      std::size_t counted = 0;  // of this work unit's trials, added to the progress
      const auto after_step = [&](std::size_t ended) {
        progress.add(LiveProgress::kTrials, ended - counted);
        counted = ended;
        progress.poll();
      };
      try {
        for (trial::TrialOutcome& outcome :
             runners.get(unit.object, unit.gripper)
                 .run(candidates, unit.ids, report.threads, trajectory, after_step)) {
          io::CandidateResult& result = outcome.result;
          if (!plan.dataset.candidates[result.record.id].stress) result.stress.reset();
          results.push_back(std::move(result));
        }
      } catch (const std::exception& e) {
        error = trial_failure(rank, unit, plan, job, e.what());
      }
      progress.add(LiveProgress::kTrials, unit.ids.size() - counted);
    }
    progress.wait_for_ranks();
    writer->write(results);
    // A rank whose trial failed took no further work unit; now, after the commit, every rank
    // learns the lowest failing rank's error, so none waits in a collective for it.
    if (const std::string failed = first_error(error, comm); !failed.empty()) {
      throw TrialError(failed);
    }
    std::uint64_t committed = results.size();
    MPI_Allreduce(MPI_IN_PLACE, &committed, 1, MPI_UINT64_T, MPI_SUM, comm);
    report.done += committed;
    progress.log_trials(report.done);
    int stop = stop_requested() ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &stop, 1, MPI_INT, MPI_MAX, comm);
    if (stop) {
      report.interrupted = report.done < pending.size();
      break;
    }
  }
  writer->close();
  report.trial_seconds = seconds_since(trial_start);
  return report;
}

}  // namespace grip::farm
