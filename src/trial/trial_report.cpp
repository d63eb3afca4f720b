#include "src/trial/trial_report.hpp"

#include <algorithm>

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

// The `per` values of gripper g's fingers from a list of every finger's, one gripper after the
// other (empty stays empty).
template <typename T>
std::vector<T> gripper_part(const std::vector<T>& all, std::size_t g, std::size_t per) {
  if (all.empty()) return {};
  const auto first = all.begin() + static_cast<std::ptrdiff_t>(g * per);
  return std::vector<T>(first, first + static_cast<std::ptrdiff_t>(per));
}

// Per gripper: its fingers' closing forces and whether each ended closing at the end of its path
// (the record's and the outcome's lists, which give the grippers' fingers one gripper after the
// other) and its own D1/D2 at the settled grasp (NaN when not measured).
nlohmann::ordered_json gripper_json(int grippers, const TrialOutcome& outcome) {
  const std::vector<double>& forces = outcome.result.record.closing_forces;
  const std::size_t per = forces.size() / static_cast<std::size_t>(grippers);
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (std::size_t g = 0; g < static_cast<std::size_t>(grippers); ++g) {
    const bool measured = g < outcome.gripper_distances.size();
    list.push_back({{"closing_forces", gripper_part(forces, g, per)},
                    {"closing_at_path_end", gripper_part(outcome.closing_at_path_end, g, per)},
                    {"d1", measured ? outcome.gripper_distances[g].d1 : TrialOutcome::nan},
                    {"d2", measured ? outcome.gripper_distances[g].d2 : TrialOutcome::nan}});
  }
  return list;
}

}  // namespace

void write_report(std::ostream& out, const TrialReport& report,
                  const std::vector<TrialOutcome>& outcomes) {
  nlohmann::ordered_json root = {{"object", report.object},
                                 {"gripper", report.gripper},
                                 {"soft", report.soft},
                                 {"threads", report.threads},
                                 {"device", report.device},
                                 {"candidates", outcomes.size()},
                                 {"wall_seconds", report.wall_seconds}};
  if (report.fin_ray) {
    root["finger_mesh"] = {{"layers", report.fin_ray->layers},
                           {"edge_length", report.fin_ray->edge_length}};
  }
  if (report.grippers > 1) root["bimanual"] = true;
  if (report.compared_solo) {
    root["solo_wall_seconds"] = report.solo_wall_seconds;
    root["speedup"] = report.solo_wall_seconds / report.wall_seconds;
    root["identical_to_solo"] = report.identical_to_solo;
    root["batch_memory_mib"] = report.batch_memory_mib;
    root["solo_memory_mib"] = report.solo_memory_mib;
    if (outcomes.size() > 1) {
      root["memory_per_added_environment_mib"] =
          report.memory_per_added_environment_mib(outcomes.size());
    }
  }
  nlohmann::ordered_json trials = nlohmann::ordered_json::array();
  for (const TrialOutcome& outcome : outcomes) {
    const io::CandidateRecord& r = outcome.result.record;
    nlohmann::ordered_json trial{{"id", r.id},
                                 {"status", io::to_string(r.status)},
                                 {"failure", io::to_string(r.failure)},
                                 {"reason", outcome.failure_reason},
                                 {"d1", r.d1},
                                 {"d2", r.d2},
                                 {"displacement", r.displacement},
                                 {"closing_forces", r.closing_forces},
                                 {"closing_at_path_end", outcome.closing_at_path_end},
                                 {"settle_displacement", outcome.settle_displacement},
                                 {"center_displacement", outcome.center_displacement},
                                 {"end_speed", outcome.end_speed},
                                 {"phase_seconds", r.phase_seconds},
                                 {"contact_friction", r.contact_friction},
                                 {"newton",
                                  {{"steps", r.newton.steps},
                                   {"iterations", r.newton.iterations},
                                   {"max_iterations", r.newton.max_iterations},
                                   {"retries", r.newton.retries}}},
                                 {"simulated_frames", r.simulated_frames},
                                 {"wall_time", r.wall_time},
                                 {"stage_seconds", stage_json(outcome.stage_seconds)},
                                 {"linear_solves",
                                  {{"factorizations", outcome.linear_solves.factorizations},
                                   {"reused", outcome.linear_solves.reused},
                                   {"cg_iterations", outcome.linear_solves.cg_iterations}}}};
    if (report.grippers > 1) trial["grippers"] = gripper_json(report.grippers, outcome);
    // A soft object's largest von Mises stress over its tets at the settled grasp (Pa).
    const auto& stress = outcome.result.stress;
    if (stress && !stress->empty()) {
      trial["peak_stress"] = *std::max_element(stress->begin(), stress->end());
    }
    trials.push_back(std::move(trial));
  }
  root["trials"] = std::move(trials);
  // One line per candidate, with every double exactly (17 digits).
  out << json::text(root, "%.17g", {{"", 0}, {"/trials", 2}}) << '\n';
}

}  // namespace grip::trial
