// The benchmarks' last lines, one JSON object each: their layout, and a scene path or PETSc
// method with quotes, backslashes and newlines kept as it is.
#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bench/batch/batch_benchmark.hpp"
#include "bench/ccd/ccd_benchmark.hpp"
#include "bench/linear/linear_benchmark.hpp"

namespace grip::bench {
namespace {

const std::string kOdd = "scenes/\"odd\" \\name\\\nsecond line.toml";

nlohmann::json parse_line(const std::string& line) {
  EXPECT_EQ(line.find('\n'), line.size() - 1) << "one line: " << line;
  return nlohmann::json::parse(line, nullptr, false);
}

TEST(BenchJsonLines, BatchLine) {
  BatchBenchmarkResult result;
  result.scene = "box.toml";
  result.threads = 2;
  result.rows = {{1, 100, 0.178327, 0.173269, 1.0291876, 828, 0, 0.9921875, 0.9921875,
                  std::numeric_limits<double>::quiet_NaN(), 0, true}};
  std::ostringstream out;
  write_json_line(out, result);
  EXPECT_EQ(
      out.str(),
      "{\"benchmark\": \"batch\", \"scene\": \"box.toml\", \"threads\": 2, \"device\": \"cpu\", "
      "\"rows\": "
      "[{\"envs\": 1, \"steps\": 100, \"sequential_s\": 0.178327, \"batched_s\": 0.173269, "
      "\"speedup\": 1.02919, \"newton_iterations\": 828, \"frozen_fraction\": 0, "
      "\"memory_mib\": 0.992188, \"memory_per_env_mib\": 0.992188, "
      "\"memory_per_added_env_mib\": null, \"failed\": 0, \"identical\": true}]}\n");

  result.scene = kOdd;
  out.str("");
  write_json_line(out, result);
  const nlohmann::json read = parse_line(out.str());
  ASSERT_FALSE(read.is_discarded()) << out.str();
  EXPECT_EQ(read["scene"], kOdd);
}

TEST(BenchJsonLines, LinearLine) {
  LinearBenchmarkResult result;
  result.ranks = 2;
  result.method = "cg + gamg";
  result.crossover_dofs = 0;
  result.source = LinearSystemSource::kSqueeze;
  result.rows = {{0.01, 1234, 56789, 0.0123456789, 3.75, 2.5, 0.125, 0.5, 17, 2.5e-9}};
  result.peak_rss_mib = {86.5, 48.25};
  std::ostringstream out;
  write_json_line(out, result);
  EXPECT_EQ(out.str(),
            "{\"benchmark\":\"linear\",\"system\":\"squeeze\",\"ranks\":2,\"method\":\"cg + "
            "gamg\",\"crossover_dofs\":0,"
            "\"peak_rss_mib\":[86.5,48.25],"
            "\"rows\":[{\"cell\":0.01,\"dofs\":1234,\"nonzeros\":56789,\"direct_s\":0.0123457,"
            "\"direct_mib\":3.75,\"factor_mib\":2.5,\"factor_gflop\":0.125,\"petsc_s\":0.5,"
            "\"iterations\":17,\"relative_difference\":2.5e-09}]}\n");

  result.method = kOdd;
  out.str("");
  write_json_line(out, result);
  const nlohmann::json read = parse_line(out.str());
  ASSERT_FALSE(read.is_discarded()) << out.str();
  EXPECT_EQ(read["method"], kOdd);
}

TEST(BenchJsonLines, CcdSummary) {
  CcdBenchmarkResult result;
  result.queries = 279;
  result.false_positives = 45;
  result.ns_per_query = 205.4321;
  EXPECT_EQ(summary_json(result),
            R"({"queries":279,"false_negatives":0,"false_positives":45,"ns_per_query":205.4})");
}

}  // namespace
}  // namespace grip::bench
