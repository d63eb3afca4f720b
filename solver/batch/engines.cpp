#include "solver/batch/engines.hpp"

#include <stdexcept>

#include "solver/batch/batch.hpp"
#include "solver/batch/parallel_engine.hpp"

namespace grip::solver {

const char* device_name(EngineDevice device) {
  return device == EngineDevice::kHost ? "host" : "cpu";
}

EngineDevice engine_device(const std::string& name) {
  if (name == "host") return EngineDevice::kHost;
  if (name == "cpu") return EngineDevice::kCpu;
  throw std::invalid_argument("no engine runs on device '" + name + "': cpu or host");
}

std::unique_ptr<Engine> make_engine(EngineDevice device, int threads) {
  if (device == EngineDevice::kHost) return std::make_unique<ParallelEngine>(threads);
  return std::make_unique<Batch>(threads);
}

}  // namespace grip::solver
