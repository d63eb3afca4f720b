#pragma once
// `grip bench hard`: runs the hard-case suite (or some of its cases), prints a table, writes
// <out>/hard.md, <out>/hard.csv (one row per case), <out>/hard_steps.csv (one row per accepted
// step) and plots <out>/hard.png.
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "bench/hard/hard_suite.hpp"

namespace grip::bench {

struct HardBenchmarkOptions {
  std::vector<std::string> cases;  // names; empty: every case
  int threads = 0;                 // 0: all cores
  std::filesystem::path out = "out/hard";
};

// Throws std::invalid_argument naming an unknown case.
std::vector<HardCase> select_hard_cases(const std::vector<std::string>& names);

// Runs the selected cases and writes the table, files and plot. All passed: see all_passed.
std::vector<HardCaseResult> run_hard_benchmark(const HardBenchmarkOptions& options,
                                               std::ostream& out);

bool all_passed(const std::vector<HardCaseResult>& results);

// The verdict columns in words (used by the table and the files).
std::string solver_outcome(const HardCaseResult& result);

}  // namespace grip::bench
