#include "bench/scale/commit_probe.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>

#include "farm/work_unit_claims.hpp"
#include "io/dataset_writer.hpp"
#include "io/journal.hpp"

namespace grip::bench {
namespace {

constexpr int kClaims = 2000;             // per rank
constexpr int kRounds = 7;                // commits timed per row size
constexpr int kRowsPerRank = 16;          // a round's rows per rank: 4 work units of 4
constexpr int kUnitRows = 4;              // a work unit's rows (the farm's at one thread)
constexpr int kUnitsPerRank = 15;         // unit commits timed per rank and row size
constexpr std::uint32_t kVertices = 500;  // object vertices, for the trajectory rows
constexpr std::uint32_t kFrames = 20;
constexpr std::uint32_t kGripperVertices = 8;
constexpr std::uint32_t kJoints = 1;
constexpr std::uint32_t kFingers = 2;

double now() { return MPI_Wtime(); }

double slowest(double seconds, MPI_Comm comm) {
  MPI_Allreduce(MPI_IN_PLACE, &seconds, 1, MPI_DOUBLE, MPI_MAX, comm);
  return seconds;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// One rigid object and a one-hand parallel gripper; candidates alternate between rows of the
// table only and rows with a trajectory, in two halves.
io::DatasetPlan probe_plan(std::uint32_t candidates) {
  io::DatasetPlan plan;
  io::ObjectRecord object;
  object.name = "probe";
  object.category = "box";
  object.material = {1e9, 0.4, 1000.0, 0.8};
  for (std::uint32_t v = 0; v < kVertices; ++v) {
    object.vertices.insert(object.vertices.end(), {0.001 * v, 0.002 * (v % 7), 0.003 * (v % 3)});
  }
  object.triangles = {0, 1, 2};
  plan.objects = {object};
  io::GripperRecord gripper;
  gripper.name = "probe-jaw";
  gripper.kind = "parallel";
  gripper.joint_names = {"width"};
  gripper.finger_names = {"left", "right"};
  for (std::uint32_t v = 0; v < kGripperVertices; ++v) {
    gripper.vertices.insert(gripper.vertices.end(), {0.01 * v, 0.0, 0.0});
  }
  gripper.triangles = {0, 1, 2};
  plan.grippers = {gripper};
  plan.closing_frames = kFrames / 2;
  plan.validation_frames = kFrames / 2;
  for (std::uint32_t id = 0; id < candidates; ++id) {
    plan.candidates.push_back({0, 0, id >= candidates / 2, false});
  }
  return plan;
}

io::CandidateResult probe_result(std::uint64_t id, bool trajectory) {
  io::CandidateResult result;
  io::CandidateRecord& r = result.record;
  r.id = id;
  r.hand_poses.assign(12, 0.5);
  r.joints.assign(kJoints, 0.02);
  r.status = io::Status::kSuccess;
  r.closing_forces.assign(kFingers, 3.0);
  r.wall_time = 1.0;
  if (trajectory) {
    io::TrajectoryRecord t;
    const std::size_t points = std::size_t{kFrames} * kVertices * 3;
    t.object_vertices.assign(points, 0.1f);
    t.gripper_vertices.assign(std::size_t{kFrames} * kGripperVertices * 3, 0.2f);
    t.gripper_contact_forces.assign(t.gripper_vertices.size(), 1.0f);
    t.gripper_friction_forces.assign(t.gripper_vertices.size(), 0.5f);
    t.contact_forces.assign(points, 1.0f);
    t.friction_forces.assign(points, 0.5f);
    t.object_poses.assign(std::size_t{kFrames} * 12, 0.0);
    t.hand_poses.assign(std::size_t{kFrames} * 12, 0.0);
    t.joints.assign(std::size_t{kFrames} * kJoints, 0.0);
    result.trajectory = std::move(t);
  }
  return result;
}

// A row's payload in bytes: the table's columns (about 40 values and their checksums), and a
// trajectory's frames.
double row_bytes(bool trajectory) {
  const double table = 8.0 * (12 + kJoints + kFingers + 2 + 6 + 1 + 1) + 4.0 * 4 + 2 + 4.0 * 20;
  const double frames = static_cast<double>(kFrames) *
                        (4.0 * 3 * (3.0 * kVertices + kGripperVertices) + 8.0 * (24 + kJoints));
  return trajectory ? table + frames : table;
}

// Every rank commits kUnitsPerRank work units of its own rows at once, as the farm's ranks do
// when their units end together (the worst case: all share the file at each commit); the median
// over every commit of every rank. Rank 0's share includes appending the others' journal lines.
double time_unit_commits(io::DatasetWriter& writer, std::uint64_t first, bool trajectory,
                         MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  std::vector<double> seconds;
  MPI_Barrier(comm);
  for (int unit = 0; unit < kUnitsPerRank; ++unit) {
    std::vector<io::CandidateResult> mine;
    const std::uint64_t start_row = first + (static_cast<std::uint64_t>(unit) * ranks + rank) *
                                                static_cast<std::uint64_t>(kUnitRows);
    for (int i = 0; i < kUnitRows; ++i) mine.push_back(probe_result(start_row + i, trajectory));
    const double start = now();
    writer.commit_unit(mine);
    writer.poll_journal();
    seconds.push_back(now() - start);
  }
  writer.end_units([] {});
  std::vector<double> all(seconds.size() * static_cast<std::size_t>(ranks));
  MPI_Allgather(seconds.data(), static_cast<int>(seconds.size()), MPI_DOUBLE, all.data(),
                static_cast<int>(seconds.size()), MPI_DOUBLE, comm);
  return median(all);
}

// Rank 0's cost per journal line: a line of four ids appended and fsync'd, in a scratch journal.
double time_journal_lines(const std::filesystem::path& folder, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  double seconds = 0;
  if (rank == 0) {
    const std::filesystem::path path = folder / "probe_journal";
    std::filesystem::remove(path);
    std::vector<double> lines;
    {
      io::Journal journal = io::Journal::create(path, "probe", 1000);
      const std::vector<std::uint64_t> ids = {1, 2, 3, 4};
      for (int k = 0; k < 50; ++k) {
        const double start = now();
        journal.append(ids);
        lines.push_back(now() - start);
      }
    }
    std::filesystem::remove(path);
    seconds = median(lines);
  }
  MPI_Bcast(&seconds, 1, MPI_DOUBLE, 0, comm);
  return seconds;
}

}  // namespace

ProbeResult probe_commit_costs(MPI_Comm comm, const std::filesystem::path& folder) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  ProbeResult result;
  result.ranks = ranks;

  {
    farm::WorkUnitClaims claims(comm);
    MPI_Barrier(comm);
    const double start = now();
    for (int k = 0; k < kClaims; ++k) claims.claim();
    const double mine = now() - start;
    double sum = mine;
    MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, comm);
    result.claim_seconds = sum / ranks / kClaims;
    result.claim_service = slowest(mine, comm) / (static_cast<double>(kClaims) * ranks);
  }

  const std::uint32_t per_round = static_cast<std::uint32_t>(kRowsPerRank * ranks);
  const std::uint32_t per_half = static_cast<std::uint32_t>(kUnitsPerRank * kUnitRows * ranks);
  // Rows of the table only, then rows with trajectories: the rounds', then the units'.
  const std::uint32_t candidates = 2 * (kRounds * per_round + per_half);
  const std::filesystem::path dataset = folder / ("probe_" + std::to_string(ranks) + ".h5");
  if (rank == 0) {
    std::filesystem::create_directories(folder);
    std::filesystem::remove(dataset);
    std::filesystem::remove(dataset.string() + ".journal");
  }
  MPI_Barrier(comm);
  io::Provenance provenance;
  provenance.job_file = "probe.toml";
  provenance.job_text = "[job]\nname = \"commit-probe\"\n";
  {
    io::DatasetWriter writer =
        io::DatasetWriter::create(dataset, probe_plan(candidates), provenance, comm);
    const std::uint64_t half_size = kRounds * per_round + per_half;
    for (int half = 0; half < 2; ++half) {
      std::vector<double> seconds;
      for (int round = 0; round < kRounds; ++round) {
        const std::uint64_t first =
            half * half_size + static_cast<std::uint64_t>(round) * per_round;
        std::vector<io::CandidateResult> mine;
        for (std::uint32_t i = 0; i < per_round; ++i) {
          if (static_cast<int>(i % ranks) == rank)
            mine.push_back(probe_result(first + i, half == 1));
        }
        MPI_Barrier(comm);
        const double start = now();
        writer.write(mine);
        // The farm's round end adds an error exchange and two allreduces to the write.
        std::uint64_t count = mine.size();
        MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPI_UINT64_T, MPI_SUM, comm);
        int stop = 0;
        MPI_Allreduce(MPI_IN_PLACE, &stop, 1, MPI_INT, MPI_MAX, comm);
        MPI_Allreduce(MPI_IN_PLACE, &stop, 1, MPI_INT, MPI_MAX, comm);
        seconds.push_back(slowest(now() - start, comm));
      }
      result.commits.push_back({row_bytes(half == 1) * per_round, median(seconds)});
      result.unit_commits.push_back(
          {row_bytes(half == 1) * kUnitRows,
           time_unit_commits(writer, half * half_size + kRounds * per_round, half == 1, comm)});
    }
    result.journal_seconds = time_journal_lines(folder, comm);
    writer.close();
  }
  if (rank == 0) {
    std::filesystem::remove(dataset);
    std::filesystem::remove(dataset.string() + ".journal");
  }
  return result;
}

void write_probe_json(const std::filesystem::path& file, const ProbeResult& result) {
  const auto samples = [](const std::vector<CommitSample>& list) {
    nlohmann::ordered_json array = nlohmann::ordered_json::array();
    for (const CommitSample& c : list)
      array.push_back({{"bytes", c.bytes}, {"seconds", c.seconds}});
    return array;
  };
  const nlohmann::ordered_json json = {{"ranks", result.ranks},
                                       {"claim_seconds", result.claim_seconds},
                                       {"claim_service", result.claim_service},
                                       {"commits", samples(result.commits)},
                                       {"unit_commits", samples(result.unit_commits)},
                                       {"journal_seconds", result.journal_seconds}};
  std::ofstream(file) << json.dump() << '\n';
}

ProbeResult read_probe_json(const std::filesystem::path& file) {
  std::ifstream in(file);
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
  ProbeResult result;
  try {
    result.ranks = json.at("ranks").get<int>();
    result.claim_seconds = json.at("claim_seconds").get<double>();
    result.claim_service = json.at("claim_service").get<double>();
    for (const auto& c : json.at("commits")) {
      result.commits.push_back({c.at("bytes").get<double>(), c.at("seconds").get<double>()});
    }
    for (const auto& c : json.at("unit_commits")) {
      result.unit_commits.push_back({c.at("bytes").get<double>(), c.at("seconds").get<double>()});
    }
    result.journal_seconds = json.at("journal_seconds").get<double>();
  } catch (const nlohmann::json::exception&) {
    throw std::runtime_error(file.string() + ": not the commit probe's result");
  }
  return result;
}

}  // namespace grip::bench
