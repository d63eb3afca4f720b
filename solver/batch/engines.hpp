#pragma once
// The engines behind the seam (solver/engine/engine.hpp), by where they step environments.
#include <memory>
#include <string>

#include "solver/engine/engine.hpp"

namespace grip::solver {

enum class EngineDevice {
  kCpu,   // the CPU engine (solver::Batch): one Environment per thread, CHOLMOD
  kHost,  // the data-parallel engine (solver::ParallelEngine) on the host launcher
};

// "cpu" or "host" (what --device of grip trial, grip simulate and grip bench batch takes), and
// back; another name throws std::invalid_argument.
const char* device_name(EngineDevice device);
EngineDevice engine_device(const std::string& name);

// threads = 0: all the machine's cores.
std::unique_ptr<Engine> make_engine(EngineDevice device, int threads);

}  // namespace grip::solver
