// The JSON report of `grip trial`: its layout, byte for byte, and object specs and solver
// reasons with quotes, backslashes and newlines kept as they are.
#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "src/trial/trial_report.hpp"

namespace grip::trial {
namespace {

// A held candidate and one Newton gave up on, compared with solo runs.
std::vector<TrialOutcome> two_outcomes() {
  std::vector<TrialOutcome> outcomes(2);
  io::CandidateRecord& held = outcomes[0].result.record;
  held.id = 3;
  held.status = io::Status::kSuccess;
  held.d2 = 0.0005;
  held.displacement = {1e-6, 0, 0, 0, 0, 2.5e-7};
  held.closing_forces = {51.5, 50};
  outcomes[0].closed = true;
  outcomes[0].closing_at_path_end = {false, true};
  outcomes[0].settle_displacement = 2.5e-4;
  held.newton = {70, 188, 48};
  held.wall_time = 1.25;
  held.simulated_frames = 100;
  outcomes[0].stage_seconds.broad_phase = 0.5;
  outcomes[0].stage_seconds.factorization = 0.25;
  outcomes[0].linear_solves = {12, 170, 900};
  outcomes[0].result.stress = std::vector<float>{1200.0f, 51000.0f, 300.0f};  // a soft object
  io::CandidateRecord& failed = outcomes[1].result.record;
  failed.id = 4;
  failed.status = io::Status::kFailure;
  failed.failure = io::FailureKind::kNewtonLimit;
  failed.d1 = std::numeric_limits<double>::infinity();
  failed.newton = {3, 300, 100};
  failed.wall_time = 0.5;
  failed.simulated_frames = 41;
  outcomes[1].failure_reason = "t = 0.03 s: Newton did not converge in 100 iterations";
  return outcomes;
}

TrialReport compared_report() {
  TrialReport report;
  report.object = "cylinder";
  report.gripper = "parallel-jaw";
  report.threads = 2;
  report.wall_seconds = 2.0;
  report.compared_solo = true;
  report.solo_wall_seconds = 3.0;
  report.batch_memory_mib = 10.0;
  report.solo_memory_mib = 4.0;
  return report;
}

std::string report_text(const TrialReport& report, const std::vector<TrialOutcome>& outcomes) {
  std::ostringstream out;
  write_report(out, report, outcomes);
  return out.str();
}

TEST(TrialReport, KeepsItsLayout) {
  const std::string expected = R"({
"object": "cylinder",
"gripper": "parallel-jaw",
"soft": false,
"threads": 2,
"device": "cpu",
"candidates": 2,
"wall_seconds": 2,
"solo_wall_seconds": 3,
"speedup": 1.5,
"identical_to_solo": true,
"batch_memory_mib": 10,
"solo_memory_mib": 4,
"memory_per_added_environment_mib": 6,
"trials": [
  {"id": 3, "status": "success", "failure": "none", "reason": "", "d1": 0, "d2": 0.00050000000000000001, "displacement": [9.9999999999999995e-07, 0, 0, 0, 0, 2.4999999999999999e-07], "closing_forces": [51.5, 50], "closing_at_path_end": [false, true], "settle_displacement": 0.00025000000000000001, "center_displacement": [null, null, null, null, null, null], "end_speed": [null, null, null, null, null, null], "phase_seconds": [0, 0, 0, 0, 0, 0], "contact_friction": 0, "newton": {"steps": 70, "iterations": 188, "max_iterations": 48, "retries": 0}, "simulated_frames": 100, "wall_time": 1.25, "stage_seconds": {"broad_phase": 0.5, "derivatives": 0, "assembly": 0, "factorization": 0.25, "solve": 0, "ccd": 0, "line_search": 0, "friction_lag": 0, "diagnostics": 0}, "linear_solves": {"factorizations": 12, "reused": 170, "cg_iterations": 900}, "peak_stress": 51000},
  {"id": 4, "status": "failure", "failure": "newton_limit", "reason": "t = 0.03 s: Newton did not converge in 100 iterations", "d1": null, "d2": 0, "displacement": [0, 0, 0, 0, 0, 0], "closing_forces": [], "closing_at_path_end": [], "settle_displacement": null, "center_displacement": [null, null, null, null, null, null], "end_speed": [null, null, null, null, null, null], "phase_seconds": [0, 0, 0, 0, 0, 0], "contact_friction": 0, "newton": {"steps": 3, "iterations": 300, "max_iterations": 100, "retries": 0}, "simulated_frames": 41, "wall_time": 0.5, "stage_seconds": {"broad_phase": 0, "derivatives": 0, "assembly": 0, "factorization": 0, "solve": 0, "ccd": 0, "line_search": 0, "friction_lag": 0, "diagnostics": 0}, "linear_solves": {"factorizations": 0, "reused": 0, "cg_iterations": 0}}
]
}
)";
  EXPECT_EQ(report_text(compared_report(), two_outcomes()), expected);
}

TEST(TrialReport, ObjectsAndReasonsWithQuotesBackslashesAndNewlinesSurviveARoundTrip) {
  TrialReport report = compared_report();
  report.object = "meshes/\"odd\" \\name\\\nsecond line.obj";
  report.gripper = "fin\"ray\\";
  std::vector<TrialOutcome> outcomes = two_outcomes();
  outcomes[1].failure_reason = "t = 0.03 s: \"" + report.object + "\" \\ gave up\nhere";
  const std::string text = report_text(report, outcomes);
  const nlohmann::json read = nlohmann::json::parse(text, nullptr, false);
  ASSERT_FALSE(read.is_discarded()) << text;
  EXPECT_EQ(read["object"], report.object);
  EXPECT_EQ(read["gripper"], report.gripper);
  EXPECT_EQ(read["trials"][0]["reason"], "");
  EXPECT_EQ(read["trials"][1]["reason"], outcomes[1].failure_reason);
  EXPECT_EQ(read["trials"][1]["d1"], nullptr);
  EXPECT_EQ(read["speedup"], 1.5);
}

// A bimanual report splits each trial's fingers by gripper: the first gripper's closing forces
// and path ends, then the second's; a trial whose closing did not end has none for either.
TEST(TrialReport, GivesEachGripperOfABimanualTrialItsOwnFingers) {
  TrialReport report = compared_report();
  report.grippers = 2;
  std::vector<TrialOutcome> outcomes = two_outcomes();
  outcomes[0].result.record.closing_forces = {50.0, 49.0, 48.0, 30.0};
  outcomes[0].closing_at_path_end = {false, false, false, true};
  const std::string text = report_text(report, outcomes);
  const nlohmann::json read = nlohmann::json::parse(text, nullptr, false);
  ASSERT_FALSE(read.is_discarded()) << text;
  EXPECT_EQ(read["bimanual"], true);
  const nlohmann::json& grippers = read["trials"][0]["grippers"];
  ASSERT_EQ(grippers.size(), 2u);
  EXPECT_EQ(grippers[0]["closing_forces"], nlohmann::json({50.0, 49.0}));
  EXPECT_EQ(grippers[1]["closing_forces"], nlohmann::json({48.0, 30.0}));
  EXPECT_EQ(grippers[0]["closing_at_path_end"], nlohmann::json({false, false}));
  EXPECT_EQ(grippers[1]["closing_at_path_end"], nlohmann::json({false, true}));
  EXPECT_EQ(read["trials"][1]["grippers"][1]["closing_at_path_end"], nlohmann::json::array());
}

}  // namespace
}  // namespace grip::trial
