// Fuzz target: farm job files. Anything but a config::ConfigError is a finding. The job's
// folder is the fuzzer's own, so mesh globs match only the inputs written there.
#include <cstddef>
#include <cstdint>
#include <string>

#include "farm/job.hpp"
#include "fuzz/fuzz_input.hpp"
#include "src/config/config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    grip::farm::parse_job(std::string(reinterpret_cast<const char*>(data), size),
                          grip::fuzz::input_folder() / "job.toml");
  } catch (const grip::config::ConfigError&) {
  }
  return 0;
}
