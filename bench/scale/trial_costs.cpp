#include "bench/scale/trial_costs.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

#include "io/dataset_reader.hpp"

namespace grip::bench {
namespace {

std::string class_name(const std::string& gripper, bool soft) {
  return gripper + (soft ? " x soft" : " x rigid");
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  return fields;
}

double mean(const std::vector<double>& values) {
  return values.empty() ? 0.0
                        : std::accumulate(values.begin(), values.end(), 0.0) /
                              static_cast<double>(values.size());
}

CostSamples read_csv(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot read the file");
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split(line);
  const auto column = [&](const char* name) {
    const auto at = std::find(header.begin(), header.end(), name);
    if (at == header.end()) {
      throw std::runtime_error(file.string() + ": no column '" + name +
                               "' (expected grip bench trial's trial.csv)");
    }
    return static_cast<std::size_t>(at - header.begin());
  };
  const std::size_t arm = column("arm"), settings = column("settings"), wall = column("wall_s");
  CostSamples samples;
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    const std::vector<std::string> fields = split(line);
    if (fields.size() != header.size()) {
      throw std::runtime_error(file.string() + ": row " + std::to_string(row) + " has " +
                               std::to_string(fields.size()) + " fields, the header " +
                               std::to_string(header.size()));
    }
    if (fields[settings] != "defaults") continue;
    samples[fields[arm]].push_back(std::stod(fields[wall]));
  }
  if (samples.empty()) throw std::runtime_error(file.string() + ": no run at the defaults");
  return samples;
}

}  // namespace

DatasetJob read_dataset_job(const std::filesystem::path& dataset) {
  const io::DatasetReader reader(dataset);
  const io::DatasetLayout& layout = reader.layout();
  DatasetJob out;
  out.file_bytes = std::filesystem::file_size(dataset);
  ModelJob& job = out.job;
  job.grippers = static_cast<std::uint32_t>(layout.grippers.size());
  for (std::uint32_t o = 0; o < layout.objects.size(); ++o) {
    job.object_soft.push_back(reader.object(o).soft);
  }
  std::vector<std::string> gripper_names;
  for (std::uint32_t g = 0; g < job.grippers; ++g) gripper_names.push_back(reader.gripper(g).name);
  std::vector<std::string> pair_class(layout.objects.size() * job.grippers);
  for (std::size_t p = 0; p < pair_class.size(); ++p) {
    pair_class[p] = class_name(gripper_names[p % job.grippers], job.object_soft[p / job.grippers]);
  }
  for (const io::CandidateRecord& record : reader.candidates()) {
    if (record.status == io::Status::kPending) {
      throw std::runtime_error(dataset.string() + ": candidate " + std::to_string(record.id) +
                               " is not done; the model needs every candidate's wall time");
    }
    const auto pair = static_cast<std::uint32_t>(
        layout.pair(layout.object[record.id], layout.gripper[record.id]));
    job.candidate_seconds.push_back(record.wall_time);
    job.candidate_pair.push_back(pair);
    out.samples[pair_class[pair]].push_back(record.wall_time);
  }
  for (const std::string& c : pair_class) job.class_mean.push_back(mean(out.samples[c]));
  return out;
}

CostSamples read_cost_samples(const std::filesystem::path& file) {
  if (file.extension() == ".h5") return read_dataset_job(file).samples;
  return read_csv(file);
}

ModelJob sampled_job(const CostSamples& samples, const std::vector<std::string>& grippers,
                     std::uint64_t objects, std::uint64_t candidates, double soft_fraction,
                     std::uint64_t seed) {
  if (objects == 0 || grippers.empty() || candidates < objects * grippers.size()) {
    throw std::invalid_argument("the job needs objects, grippers and a candidate per pair");
  }
  ModelJob job;
  job.grippers = static_cast<std::uint32_t>(grippers.size());
  for (std::uint64_t i = 0; i < objects; ++i) {
    job.object_soft.push_back(std::floor(static_cast<double>(i + 1) * soft_fraction) >
                              std::floor(static_cast<double>(i) * soft_fraction));
  }
  const std::uint64_t pairs = objects * grippers.size();
  std::mt19937_64 random(seed);
  for (std::uint64_t p = 0; p < pairs; ++p) {
    const std::string name =
        class_name(grippers[p % grippers.size()], job.object_soft[p / grippers.size()]);
    const auto found = samples.find(name);
    if (found == samples.end() || found->second.empty()) {
      throw std::invalid_argument("no measured trial cost for '" + name + "'");
    }
    const std::vector<double>& costs = found->second;
    job.class_mean.push_back(mean(costs));
    // candidates spread evenly: pair p gets floor((p+1) C / pairs) - floor(p C / pairs)
    const std::uint64_t count = (p + 1) * candidates / pairs - p * candidates / pairs;
    for (std::uint64_t c = 0; c < count; ++c) {
      job.candidate_seconds.push_back(costs[random() % costs.size()]);
      job.candidate_pair.push_back(static_cast<std::uint32_t>(p));
    }
  }
  return job;
}

}  // namespace grip::bench
