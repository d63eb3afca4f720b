#pragma once
// Measured trial costs for the farm model: per candidate from a dataset's `wall_time` column,
// or per run from `grip bench trial`'s trial.csv, grouped in classes "GRIPPER x rigid|soft".
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "bench/scale/farm_model.hpp"

namespace grip::bench {

// Wall seconds of single trials by class, e.g. {"fin-ray x soft": {13.1, 14.2, ...}}.
using CostSamples = std::map<std::string, std::vector<double>>;

// A finished dataset as the model's job: its candidates' wall times in id order, its pairs and
// objects. Throws std::runtime_error when a candidate is not done.
struct DatasetJob {
  ModelJob job;
  CostSamples samples;
  std::uint64_t file_bytes = 0;
};
DatasetJob read_dataset_job(const std::filesystem::path& dataset);

// trial.csv's runs at the defaults (settings "defaults"), `wall_s` by `arm`; or a dataset's
// done candidates by class. Throws std::runtime_error naming the file on a bad one.
CostSamples read_cost_samples(const std::filesystem::path& file);

// A synthetic job: `objects` objects, every k-th soft so that `soft_fraction` of them are,
// each graded by every gripper in `grippers`, `candidates` candidates spread evenly over the
// pairs; each candidate's cost drawn (deterministically from `seed`) from its class's samples;
// class_mean from the samples' means.
// Throws std::invalid_argument naming a class without samples.
ModelJob sampled_job(const CostSamples& samples, const std::vector<std::string>& grippers,
                     std::uint64_t objects, std::uint64_t candidates, double soft_fraction,
                     std::uint64_t seed);

}  // namespace grip::bench
