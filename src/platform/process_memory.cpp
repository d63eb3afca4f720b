#include "src/platform/process_memory.hpp"

#include <malloc.h>

#include <fstream>
#include <string>

namespace grip::platform {
namespace {

// A field of /proc/self/status in kB (VmRSS: resident now, VmHWM: peak resident).
double proc_status_kib(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string key;
  double value = 0.0;
  while (status >> key) {
    if (key == field + ":") {
      status >> value;
      return value;
    }
    status.ignore(1 << 12, '\n');
  }
  return 0.0;
}

}  // namespace

MemoryPeak::MemoryPeak() {
  malloc_trim(0);
  std::ofstream("/proc/self/clear_refs") << "5";
  baseline_kib_ = proc_status_kib("VmRSS");
}

double MemoryPeak::mib() const { return (proc_status_kib("VmHWM") - baseline_kib_) / 1024.0; }

}  // namespace grip::platform
