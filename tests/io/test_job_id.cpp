// The job id: SHA-256 of the job text, a NUL and the decimal seed (values from Python's
// hashlib), so any edit to the job or a new seed names another job.
#include <gtest/gtest.h>

#include "io/provenance.hpp"

namespace grip::io {
namespace {

TEST(JobId, IsTheSha256OfTextNulAndSeed) {
  // hashlib.sha256(b'abc\x000').hexdigest()
  EXPECT_EQ(job_id("abc", 0), "e16f2935cab918f9b90988378ba435fe71dcb145781b965a08383c77a5450f18");
  // hashlib.sha256(b'[job]\nname = "x"\n\x0042').hexdigest()
  EXPECT_EQ(job_id("[job]\nname = \"x\"\n", 42),
            "c75528d26b8feb2d9e76e814beaaa2b665e34cd4d2955d5a51de1c98ee375a04");
}

TEST(JobId, ChangesWithTheTextAndTheSeed) {
  EXPECT_NE(job_id("a", 1), job_id("a ", 1));
  EXPECT_NE(job_id("a", 1), job_id("a", 2));
  // The separator keeps text and seed apart: "a1" + seed 2 is not "a" + seed 12.
  EXPECT_NE(job_id("a1", 2), job_id("a", 12));
}

}  // namespace
}  // namespace grip::io
