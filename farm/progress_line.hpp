#pragma once
// Rank 0's progress line: what it says (planning; trials with rate and ETA) and how it is shown:
// on a terminal one line rewritten in place, elsewhere a log line now and then (docs/farm.md).
#include <cstdint>
#include <cstdio>
#include <string>

namespace grip::farm {

// "planning: 3/5 objects prepared, 24 candidates synthesized for 4/10 (object, gripper) pairs,
// 12 s"
std::string plan_progress_text(std::uint64_t objects, std::uint64_t objects_total,
                               std::uint64_t candidates, std::uint64_t pairs,
                               std::uint64_t pairs_total, double seconds);
// "48/120 trials (40.0%), 1.25 trials/s, ETA 58 s"
std::string trial_progress_text(std::uint64_t done, std::uint64_t total, double seconds);

class ProgressLine {
 public:
  static constexpr double kTerminalInterval = 1.0;  // s between two rewrites of the line
  static constexpr double kLogInterval = 5.0;       // s at least between two log lines

  // interval: seconds between lines, < 0 for the default of where they go. terminal: rewrite
  // one line in place on `out`; otherwise log lines (spdlog).
  ProgressLine(double interval, bool terminal, std::FILE* out = stderr);
  ~ProgressLine();  // erases the line in place
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  static bool stderr_is_terminal();

  // Whether `interval` has passed since the last line, at `now` (s, any fixed origin).
  bool due(double now) const;
  // Shows `text` if due and the log level lets info through: in place on a terminal; as a log
  // line only if `tally` (a count of what has ended so far) moved since the last one. Returns
  // whether it showed.
  bool show(double now, std::uint64_t tally, const std::string& text);
  // A log line now, whatever the interval; on a terminal the line in place is erased first.
  void log(double now, std::uint64_t tally, const std::string& text);

 private:
  void erase();

  double interval_;
  bool terminal_;
  std::FILE* out_;
  double last_ = 0;  // when the last line was shown
  std::uint64_t last_tally_ = 0;
  bool shown_ = false;  // a line in place is on the terminal
};

}  // namespace grip::farm
