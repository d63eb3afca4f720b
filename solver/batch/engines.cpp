#include "solver/batch/engines.hpp"

#include "solver/batch/batch.hpp"
#include "solver/batch/parallel_engine.hpp"

namespace grip::solver {

const char* device_name(EngineDevice device) {
  return device == EngineDevice::kHost ? "host" : "cpu";
}

std::unique_ptr<Engine> make_engine(EngineDevice device, int threads) {
  if (device == EngineDevice::kHost) return std::make_unique<ParallelEngine>(threads);
  return std::make_unique<Batch>(threads);
}

}  // namespace grip::solver
