#include "farm/progress_line.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cmath>

namespace grip::farm {
namespace {

std::string duration(double seconds) {
  const auto s = static_cast<long long>(std::llround(seconds));
  if (s < 120) return fmt::format("{} s", s);
  if (s < 7200) return fmt::format("{} min {} s", s / 60, s % 60);
  return fmt::format("{} h {} min", s / 3600, (s % 3600) / 60);
}

}  // namespace

std::string plan_progress_text(std::uint64_t objects, std::uint64_t objects_total,
                               std::uint64_t candidates, std::uint64_t pairs,
                               std::uint64_t pairs_total, double seconds) {
  return fmt::format(
      "planning: {}/{} objects prepared, {} candidates synthesized for {}/{} (object, gripper) "
      "pairs, {}",
      objects, objects_total, candidates, pairs, pairs_total, duration(seconds));
}

std::string trial_progress_text(std::uint64_t done, std::uint64_t total, double seconds) {
  const double fraction = total ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
  const double rate = seconds > 0 ? static_cast<double>(done) / seconds : 0.0;
  std::string line =
      fmt::format("{}/{} trials ({:.1f}%), {:.2f} trials/s", done, total, 100.0 * fraction, rate);
  if (done < total && rate > 0) {
    line += ", ETA " + duration(static_cast<double>(total - done) / rate);
  }
  return line;
}

ProgressLine::ProgressLine(double interval, bool terminal, std::FILE* out)
    : interval_(interval >= 0 ? interval
                : terminal    ? kTerminalInterval
                              : kLogInterval),
      terminal_(terminal),
      out_(out) {}

ProgressLine::~ProgressLine() { erase(); }

bool ProgressLine::stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

bool ProgressLine::due(double now) const { return now - last_ >= interval_; }

bool ProgressLine::show(double now, std::uint64_t tally, const std::string& text) {
  if (!due(now) || (!terminal_ && tally == last_tally_)) return false;
  if (!spdlog::should_log(spdlog::level::info)) return false;  // -q quiets the line in place too
  last_ = now;
  last_tally_ = tally;
  if (terminal_) {
    std::fprintf(out_, "\r%s\033[K", text.c_str());  // \033[K: clear what a longer line left
    std::fflush(out_);
    shown_ = true;
  } else {
    spdlog::info("{}", text);
  }
  return true;
}

void ProgressLine::log(double now, std::uint64_t tally, const std::string& text) {
  erase();
  last_ = now;
  last_tally_ = tally;
  spdlog::info("{}", text);
}

void ProgressLine::erase() {
  if (!shown_) return;
  std::fprintf(out_, "\r\033[K");
  std::fflush(out_);
  shown_ = false;
}

}  // namespace grip::farm
