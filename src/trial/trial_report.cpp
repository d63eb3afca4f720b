#include "src/trial/trial_report.hpp"

#include <nlohmann/json.hpp>

#include "src/json/json_text.hpp"

namespace grip::trial {
namespace {

nlohmann::ordered_json stage_json(const solver::StageSeconds& s) {
  return {{"broad_phase", s.broad_phase},
          {"derivatives", s.derivatives},
          {"assembly", s.assembly},
          {"factorization", s.factorization},
          {"solve", s.solve},
          {"ccd", s.ccd},
          {"line_search", s.line_search},
          {"friction_lag", s.friction_lag},
          {"diagnostics", s.diagnostics}};
}

}  // namespace

void write_report(std::ostream& out, const TrialReport& report,
                  const std::vector<TrialOutcome>& outcomes) {
  nlohmann::ordered_json root = {
      {"object", report.object},       {"gripper", report.gripper},
      {"soft", report.soft},           {"threads", report.threads},
      {"candidates", outcomes.size()}, {"wall_seconds", report.wall_seconds}};
  if (report.compared_solo) {
    root["solo_wall_seconds"] = report.solo_wall_seconds;
    root["speedup"] = report.solo_wall_seconds / report.wall_seconds;
    root["identical_to_solo"] = report.identical_to_solo;
  }
  nlohmann::ordered_json trials = nlohmann::ordered_json::array();
  for (const TrialOutcome& outcome : outcomes) {
    const io::CandidateRecord& r = outcome.result.record;
    trials.push_back(nlohmann::ordered_json{{"id", r.id},
                                            {"status", io::to_string(r.status)},
                                            {"failure", io::to_string(r.failure)},
                                            {"reason", outcome.failure_reason},
                                            {"d1", r.d1},
                                            {"d2", r.d2},
                                            {"displacement", r.displacement},
                                            {"closing_forces", r.closing_forces},
                                            {"settle_displacement", outcome.settle_displacement},
                                            {"center_displacement", outcome.center_displacement},
                                            {"contact_friction", r.contact_friction},
                                            {"newton",
                                             {{"steps", r.newton.steps},
                                              {"iterations", r.newton.iterations},
                                              {"max_iterations", r.newton.max_iterations},
                                              {"retries", r.newton.retries}}},
                                            {"wall_time", r.wall_time},
                                            {"stage_seconds", stage_json(outcome.stage_seconds)}});
  }
  root["trials"] = std::move(trials);
  // One line per candidate, with every double exactly (17 digits).
  out << json::text(root, "%.17g", {{"", 0}, {"/trials", 2}}) << '\n';
}

}  // namespace grip::trial
