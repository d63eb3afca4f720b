#include "bench/scale/farm_model.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace grip::bench {
namespace {

struct Unit {
  std::uint32_t pair = 0;
  double seconds = 0;  // its trials, one after another on the rank's core
  std::uint64_t candidates = 0;
};

// The farm's make_work_units: pending candidates in id order, cut at each change of pair and
// at `size` candidates.
std::vector<Unit> work_units(const ModelJob& job) {
  std::vector<Unit> units;
  std::uint64_t in_unit = 0;
  for (std::size_t id = 0; id < job.candidate_seconds.size(); ++id) {
    const std::uint32_t pair = job.candidate_pair[id];
    if (units.empty() || units.back().pair != pair ||
        in_unit == static_cast<std::uint64_t>(job.work_unit_size)) {
      units.push_back({pair, 0, 0});
      in_unit = 0;
    }
    units.back().seconds += job.candidate_seconds[id];
    ++units.back().candidates;
    ++in_unit;
  }
  return units;
}

// RunnerCache: a rank keeps the scenes of the last two pairs it built, oldest dropped first.
class SceneCache {
 public:
  bool hit(std::uint32_t pair) {
    if (std::find(kept_.begin(), kept_.end(), pair) != kept_.end()) return true;
    if (kept_.size() == 2) kept_.erase(kept_.begin());
    kept_.push_back(pair);
    return false;
  }

 private:
  std::vector<std::uint32_t> kept_;
};

double log2_ranks(int ranks) { return std::log2(static_cast<double>(ranks)); }

// Rank-parallel planning: object i prepared on rank i mod P, pair u synthesized on rank
// u mod P, each phase followed by one broadcast per item.
double plan_seconds(const ModelJob& job, const FarmCosts& costs, int ranks) {
  const std::size_t objects = job.object_soft.size();
  const std::size_t pairs = objects * job.grippers;
  std::vector<double> prepare(ranks, 0.0), synthesize(ranks, 0.0);
  for (std::size_t i = 0; i < objects; ++i) {
    prepare[i % ranks] += job.object_soft[i] ? costs.prepare_soft : costs.prepare_rigid;
  }
  std::vector<std::uint64_t> per_pair(pairs, 0);
  for (const std::uint32_t pair : job.candidate_pair) ++per_pair[pair];
  for (std::size_t u = 0; u < pairs; ++u) {
    synthesize[u % ranks] += costs.synthesis * static_cast<double>(per_pair[u]);
  }
  const double broadcast = costs.broadcast_per_log2 * log2_ranks(ranks);
  return *std::max_element(prepare.begin(), prepare.end()) +
         *std::max_element(synthesize.begin(), synthesize.end()) +
         static_cast<double>(objects + pairs) * broadcast;
}

// The farm's order of work units, or, as a what-if, the costliest class first.
std::vector<Unit> ordered_units(const ModelJob& job, const ModelOptions& options) {
  std::vector<Unit> units = work_units(job);
  if (options.order == UnitOrder::kHeaviestFirst) {
    std::stable_sort(units.begin(), units.end(), [&](const Unit& a, const Unit& b) {
      return job.class_mean[a.pair] > job.class_mean[b.pair];
    });
  }
  return units;
}

// The dataset's file under unit commits: it takes one commit's bytes at a time.
class SharedFile {
 public:
  explicit SharedFile(double now) : free_(now) {}
  // When a commit of `bytes` that starts at `t` is done.
  double commit(double t, double bytes, const CommitModel& model) {
    free_ = std::max(t, free_) + (model.bandwidth > 0 ? bytes / model.bandwidth : 0.0);
    return free_ + model.latency;
  }

 private:
  double free_;
};

// Rank 0's journal: one fsync'd line at a time, each holding every unit whose ids arrived
// before it starts; rank 0 owes each line's time until it pays it.
class RankZeroJournal {
 public:
  explicit RankZeroJournal(double now) : end_(now) {}
  void arrive(double t, double line_seconds) {
    if (t <= start_) return;  // in the line already waiting to start
    start_ = std::max(t, end_);
    end_ = start_ + line_seconds;
    owed_ += line_seconds;
  }
  double pay() { return std::exchange(owed_, 0.0); }
  double owed() const { return owed_; }
  double end() const { return end_; }  // of the last line

 private:
  double start_ = -1, end_, owed_ = 0;
};

}  // namespace

double CommitModel::seconds(int ranks, double bytes) const {
  return latency + per_log2 * log2_ranks(ranks) + (bandwidth > 0 ? bytes / bandwidth : 0.0);
}

ModelRun simulate_farm(const ModelJob& job, const FarmCosts& costs, int ranks,
                       const ModelOptions& options) {
  if (ranks < 1 || job.work_unit_size < 1 || job.round_work_units < 1 ||
      job.candidate_pair.size() != job.candidate_seconds.size()) {
    throw std::invalid_argument("simulate_farm: ranks, unit and round sizes must be positive");
  }
  ModelRun run;
  run.ranks = ranks;
  run.startup = costs.startup;
  run.plan = plan_seconds(job, costs, ranks);

  const std::vector<Unit> units = ordered_units(job, options);
  run.units = units.size();
  const std::uint64_t per_round = options.rounds
                                      ? static_cast<std::uint64_t>(job.round_work_units) * ranks
                                      : std::max<std::uint64_t>(units.size(), 1);
  run.rounds = (units.size() + per_round - 1) / per_round;

  std::vector<SceneCache> scenes(ranks);
  // (time, rank, what): a rank claims its next unit (0), or, unit by unit, commits its last (1).
  using Event = std::tuple<double, int, int>;
  double now = 0;
  for (std::uint64_t round = 0; round < run.rounds; ++round) {
    const std::uint64_t first = round * per_round;
    const std::uint64_t count = std::min<std::uint64_t>(per_round, units.size() - first);
    std::priority_queue<Event, std::vector<Event>, std::greater<>> ready;
    for (int r = 0; r < ranks; ++r) ready.push({now, r, 0});
    std::vector<double> finished(ranks, now), unwritten(ranks, 0.0);
    double counter_free = now;  // rank 0's counter serves one claim at a time
    SharedFile file(now);
    RankZeroJournal journal(now);
    std::uint64_t next = 0;
    double bytes = 0;
    while (!ready.empty()) {
      const auto [t, r, what] = ready.top();
      ready.pop();
      if (what == 1) {
        const double written = file.commit(t, unwritten[r], costs.unit_commit);
        run.committing += written - t;
        if (r != 0) journal.arrive(written, costs.journal_line);
        ready.push({written, r, 0});
        continue;
      }
      if (r == 0 && journal.owed() > 0) {  // rank 0 writes the lines owed, then claims
        const double lines = journal.pay();
        run.committing += lines;
        ready.push({t + lines, 0, 0});
        continue;
      }
      const double start = std::max(t + 0.5 * costs.claim.latency, counter_free);
      counter_free = start + costs.claim.service;
      const double answered = counter_free + 0.5 * costs.claim.latency;
      run.claiming += answered - t;
      const std::uint64_t k = next++;
      if (k >= count) {  // everything is handed out: this rank waits for the others
        finished[r] = answered;
        continue;
      }
      const Unit& unit = units[first + k];
      const double trials = unit.seconds + (scenes[r].hit(unit.pair) ? 0.0 : costs.scene_build);
      const double unit_bytes = costs.bytes_per_candidate * static_cast<double>(unit.candidates);
      run.work += trials;
      bytes += unit_bytes;
      unwritten[r] = unit_bytes;
      ready.push({answered + trials, r, options.rounds ? 0 : 1});
    }
    // Rank 0 writes the lines still owed while it waits for the others' last units.
    const double end = std::max(*std::max_element(finished.begin(), finished.end()), journal.end());
    for (const double f : finished) run.idle += end - f;
    const double lines = journal.pay();
    run.idle -= lines;
    run.committing += lines;
    const double commit = options.rounds ? costs.commit.seconds(ranks, bytes) : 0.0;
    run.committing += commit * ranks;
    now = end + commit;
  }
  run.trial_phase = now;
  run.total = run.startup + run.plan + run.trial_phase;
  return run;
}

}  // namespace grip::bench
