#pragma once
// --device of grip trial, grip simulate and grip bench batch: the engine that steps the batch
// (solver/batch/engines.hpp): cpu, host (the data-parallel engine on the CPU) or cuda.
#include <string>

#include "app/cli/command_line.hpp"

namespace grip::cli {

inline const char* device_help() {
  return "The engine: cpu (one environment per thread, CHOLMOD), host (the data-parallel engine "
         "on the CPU) or cuda";
}

inline Check device_check() { return Check::one_of({"cpu", "host", "cuda"}); }

// For the command's on_check: --device cuda has no engine to run on yet.
inline void refuse_cuda_device(const std::string& device) {
  if (device != "cuda") return;
  throw UsageError("--device cuda",
                   "this grip has no CUDA engine to step environments on yet (the GPU runs "
                   "grip-gpu-check's stage checks only); use --device host, the same "
                   "data-parallel engine on the CPU");
}

}  // namespace grip::cli
