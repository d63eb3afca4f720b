#pragma once
// Where a dataset came from: the job file verbatim, its seed, the grip build and the resolved
// parameters. job_id() names the job; a dataset and its journal carry it so that a resume can
// refuse a file made by another job.
#include <cstdint>
#include <string>
#include <vector>

namespace grip::io {

struct Parameter {
  std::string key;    // dotted job key, e.g. "physics.dt"
  std::string value;  // as resolved for this run, e.g. "0.01"
};

struct Provenance {
  std::string job_file;  // the path the job was read from, as given
  std::string job_text;  // the job file's text, verbatim
  std::uint64_t seed = 0;
  std::string grip_version;
  std::string git_revision;
  std::vector<Parameter> parameters;
};

// SHA-256 (lower-case hex) of the job text and the seed: equal for the same job and seed,
// different for any other.
std::string job_id(const std::string& job_text, std::uint64_t seed);

}  // namespace grip::io
