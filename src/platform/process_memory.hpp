#pragma once
// The process's resident memory, for what a batch of environments costs (grip bench batch,
// grip trial --compare-solo). Linux: it reads and resets /proc/self.

namespace grip::platform {

// The peak resident memory of what runs after construction, above what was resident then.
class MemoryPeak {
 public:
  // Returns freed heap pages to the system and restarts the kernel's peak-resident counter, so
  // that the peak read later is the peak of what runs from here on.
  MemoryPeak();
  // MiB above the baseline at the highest point since construction.
  double mib() const;

 private:
  double baseline_kib_;
};

}  // namespace grip::platform
