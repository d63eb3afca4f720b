// Fuzz target: scene files (grip simulate's reader). Anything but a config::ConfigError is a
// finding.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_input.hpp"
#include "src/config/config.hpp"
#include "src/scene/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    grip::scene::load_scene_file(grip::fuzz::write_input(data, size, "scene.toml"));
  } catch (const grip::config::ConfigError&) {
  }
  return 0;
}
