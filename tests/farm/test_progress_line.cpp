// The farm's progress line: its text, one line rewritten in place on a terminal, and log lines
// only when something moved. Times are given, not measured.
#include "farm/progress_line.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace grip::farm {
namespace {

std::string written(std::FILE* file) {
  std::fflush(file);
  std::rewind(file);
  std::string text;
  for (int c = std::fgetc(file); c != EOF; c = std::fgetc(file))
    text.push_back(static_cast<char>(c));
  return text;
}

TEST(ProgressLine, Texts) {
  EXPECT_EQ(trial_progress_text(48, 120, 38.4), "48/120 trials (40.0%), 1.25 trials/s, ETA 58 s");
  EXPECT_EQ(trial_progress_text(0, 10, 5.0), "0/10 trials (0.0%), 0.00 trials/s");
  EXPECT_EQ(trial_progress_text(10, 10, 4.0), "10/10 trials (100.0%), 2.50 trials/s");
  EXPECT_EQ(trial_progress_text(1, 1000, 1.0),
            "1/1000 trials (0.1%), 1.00 trials/s, ETA 16 min 39 s");
  EXPECT_EQ(plan_progress_text(3, 5, 24, 4, 10, 12.2),
            "planning: 3/5 objects prepared, 24 candidates synthesized for 4/10 (object, gripper) "
            "pairs, 12 s");
}

TEST(ProgressLine, TerminalRewritesOneLineInPlaceEveryInterval) {
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  {
    ProgressLine line(1.0, true, out);
    EXPECT_FALSE(line.show(0.5, 1, "early"));  // the interval has not passed
    EXPECT_TRUE(line.show(1.0, 1, "first"));
    EXPECT_FALSE(line.show(1.5, 2, "soon"));
    EXPECT_TRUE(line.show(2.0, 2, "second"));
    EXPECT_TRUE(line.show(3.0, 2, "same tally"));  // a terminal shows the time going on
  }                                                // erased at the end
  EXPECT_EQ(written(out), "\rfirst\033[K\rsecond\033[K\rsame tally\033[K\r\033[K");
  std::fclose(out);
}

TEST(ProgressLine, LogLinesOnlyWhenSomethingMoved) {
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  {
    ProgressLine line(0.0, false, out);
    EXPECT_FALSE(line.show(1.0, 0, "nothing yet"));
    EXPECT_TRUE(line.show(2.0, 1, "one"));
    EXPECT_FALSE(line.show(3.0, 1, "still one"));
    line.log(4.0, 2, "committed");
    EXPECT_FALSE(line.show(5.0, 2, "two"));  // the log line said it
    EXPECT_TRUE(line.show(6.0, 3, "three"));
  }
  EXPECT_EQ(written(out), "");  // log lines go to the log, never in place
  std::fclose(out);

  ProgressLine slow(5.0, false, nullptr);
  EXPECT_FALSE(slow.show(4.0, 1, "too soon"));
  EXPECT_TRUE(slow.show(5.0, 1, "due"));
}

}  // namespace
}  // namespace grip::farm
