#pragma once
// A small synthetic dataset for the io tests: a plan with rigid and soft objects, a one-hand
// soft parallel gripper and a two-hand gripper, some candidates with trajectories, stress and
// finger stress, and deterministic pseudo-random results that depend only on (seed, candidate
// id).
#include <cstdint>
#include <string>

#include "io/candidate_record.hpp"
#include "io/dataset_layout.hpp"
#include "io/dataset_plan.hpp"
#include "io/provenance.hpp"

namespace grip::io::testing {

DatasetPlan synthetic_plan(std::uint32_t candidates);
Provenance synthetic_provenance(const std::string& job_text, std::uint64_t seed);
// The result a worker would hand the writer for candidate `id`: sizes follow the layout,
// a trajectory and stresses exactly where the plan gave slots.
CandidateResult synthetic_result(const DatasetLayout& layout, std::uint64_t id, std::uint64_t seed);

}  // namespace grip::io::testing
