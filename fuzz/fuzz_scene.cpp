// Fuzz target: scene files (grip simulate's reader). Anything but a config::ConfigError is a
// finding. FEM bodies are limited to kFuzzMaxTets, as `grip simulate --max-tets` limits them:
// a scene within the default limit may take minutes to mesh under the sanitizers (a 5 m box at
// 5 mm, 3.5 million tets), which says nothing about the reader's checks and would stop the
// fuzzer on a timeout.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_input.hpp"
#include "src/config/config.hpp"
#include "src/scene/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    constexpr double kFuzzMaxTets = 20'000;
    grip::scene::load_scene_file(grip::fuzz::write_input(data, size, "scene.toml"), kFuzzMaxTets);
  } catch (const grip::config::ConfigError&) {
  }
  return 0;
}
