#include "bench/peer/peer_report.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>

#include "bench/common/table_text.hpp"
#include "bench/peer/mujoco_trial.hpp"
#include "src/json/json_text.hpp"

namespace grip::bench {
namespace fs = std::filesystem;
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

double mean(const std::vector<double>& v) {
  return v.empty() ? kNan
                   : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double median(std::vector<double> v) {
  if (v.empty()) return kNan;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// One engine's view of a candidate.
struct EngineView {
  const std::string& verdict;
  double d1, d2, cpu;
};

EngineView grip_view(const PeerTrial& t) {
  return {t.grip_verdict, t.grip_d1, t.grip_d2, t.grip_cpu_seconds};
}
EngineView mujoco_view(const PeerTrial& t) {
  return {t.mujoco_verdict, t.mujoco_d1, t.mujoco_d2, t.mujoco_cpu_seconds};
}

PeerEngineStats engine_stats(const std::vector<const PeerTrial*>& trials,
                             EngineView (*view)(const PeerTrial&)) {
  PeerEngineStats s;
  std::vector<double> d1, d2, cpu;
  for (const PeerTrial* t : trials) {
    const EngineView v = view(*t);
    ++s.verdicts[v.verdict];
    cpu.push_back(v.cpu);
    if (v.verdict != "success") continue;
    ++s.held;
    if (!std::isnan(v.d1)) d1.push_back(v.d1);
    if (!std::isnan(v.d2)) d2.push_back(v.d2);
  }
  s.d1_mean = mean(d1);
  s.d1_median = median(d1);
  s.d2_mean = mean(d2);
  s.d2_median = median(d2);
  s.cpu_mean = mean(cpu);
  s.cpu_median = median(cpu);
  return s;
}

PeerTally tally(const std::string& gripper, const std::string& category,
                const std::vector<const PeerTrial*>& trials) {
  PeerTally t;
  t.gripper = gripper;
  t.category = category;
  std::vector<const PeerTrial*> compared;
  for (const PeerTrial* p : trials) {
    ++t.candidates;
    if (refused_by_grip(*p)) {
      ++t.refused;
      continue;
    }
    compared.push_back(p);
    const bool grip_held = p->grip_verdict == "success";
    const bool mujoco_held = p->mujoco_verdict == "success";
    if (grip_held == mujoco_held) ++t.agree;
    if (mujoco_held && !grip_held) ++t.mujoco_only;
    if (grip_held && !mujoco_held) ++t.grip_only;
  }
  t.compared = static_cast<int>(compared.size());
  std::vector<double> penetration;
  for (const PeerTrial* p : compared) {
    penetration.push_back(p->mujoco_penetration);
    t.mujoco_inverting += p->mujoco_inverted_tets > 0;
  }
  t.mujoco_penetration_median = median(penetration);
  t.mujoco_penetration_max =
      penetration.empty() ? kNan : *std::max_element(penetration.begin(), penetration.end());
  t.grip = engine_stats(compared, grip_view);
  t.mujoco = engine_stats(compared, mujoco_view);
  return t;
}

std::string cm_pair(double mean, double median) {
  return fixed_or_dash(mean * 100, 3) + " / " + fixed_or_dash(median * 100, 3);
}

std::string verdict_counts(const std::map<std::string, int>& verdicts) {
  std::string text;
  for (const auto& [verdict, n] : verdicts) {
    if (!text.empty()) text += ", ";
    text += std::to_string(n) + " " + verdict;
  }
  return text.empty() ? "-" : text;
}

}  // namespace

std::vector<PeerTally> peer_tallies(const PeerResult& result) {
  std::vector<std::string> grippers, categories;
  for (const PeerTrial& t : result.trials) {
    if (std::find(grippers.begin(), grippers.end(), t.gripper) == grippers.end()) {
      grippers.push_back(t.gripper);
    }
    if (std::find(categories.begin(), categories.end(), t.category) == categories.end()) {
      categories.push_back(t.category);
    }
  }
  std::vector<PeerTally> tallies;
  for (const std::string& gripper : grippers) {
    std::vector<const PeerTrial*> all;
    for (const std::string& category : categories) {
      std::vector<const PeerTrial*> trials;
      for (const PeerTrial& t : result.trials) {
        if (t.gripper == gripper && t.category == category) trials.push_back(&t);
      }
      if (trials.empty()) continue;
      all.insert(all.end(), trials.begin(), trials.end());
      tallies.push_back(tally(gripper, category, trials));
    }
    tallies.push_back(tally(gripper, "all", all));
  }
  return tallies;
}

void write_peer_table(std::ostream& out, const std::vector<PeerTally>& tallies) {
  out << "| gripper | category | compared | held: grip | held: MuJoCo | same verdict | MuJoCo "
         "holds, grip drops | grip holds, MuJoCo drops | D1 cm grip (mean / median) | D1 cm "
         "MuJoCo | D2 cm grip | D2 cm MuJoCo | MuJoCo's deepest contact, mm (median / max) | "
         "MuJoCo inverted tets (trials) | CPU s per trial: grip (mean / median) | MuJoCo "
         "|\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const PeerTally& t : tallies) {
    out << "| " << t.gripper << " | " << t.category << " | " << t.compared << " | " << t.grip.held
        << " | " << t.mujoco.held << " | " << t.agree << " | " << t.mujoco_only << " | "
        << t.grip_only << " | " << cm_pair(t.grip.d1_mean, t.grip.d1_median) << " | "
        << cm_pair(t.mujoco.d1_mean, t.mujoco.d1_median) << " | "
        << cm_pair(t.grip.d2_mean, t.grip.d2_median) << " | "
        << cm_pair(t.mujoco.d2_mean, t.mujoco.d2_median) << " | "
        << fixed_or_dash(t.mujoco_penetration_median * 1e3, 3) << " / "
        << fixed_or_dash(t.mujoco_penetration_max * 1e3, 3) << " | " << t.mujoco_inverting << " | "
        << fixed_or_dash(t.grip.cpu_mean, 3) << " / " << fixed_or_dash(t.grip.cpu_median, 3)
        << " | " << fixed_or_dash(t.mujoco.cpu_mean, 3) << " / "
        << fixed_or_dash(t.mujoco.cpu_median, 3) << " |\n";
  }
}

std::string peer_file_stem(const std::string& gripper) {
  return gripper == "parallel-jaw" ? "peer" : "peer-" + gripper;
}

void write_peer_files(const fs::path& out, const PeerResult& result,
                      const std::vector<PeerTally>& tallies) {
  fs::create_directories(out);
  const std::string stem = peer_file_stem(result.gripper);
  std::ofstream md(out / (stem + ".md"));
  const trial::TrialParameters& p = result.parameters;
  const MujocoSettings s;
  md << "# grip bench peer\n\nThe same synthesized candidates validated by grip (IPC, dt "
     << p.sim.dt << " s) and by MuJoCo " << result.mujoco_version << " (dt "
     << (result.gripper == "fin-ray" ? s.flex_timestep : s.timestep)
     << " s, the object's convex hull, multiccd), rigid objects; grip force " << p.grip_force
     << " N, gravity " << p.gravity_magnitude << " m/s^2 for " << p.phase_duration
     << " s along +x, -x, +y, -y, +z, -z; held: still in contact and slip "
     << "below " << p.displacement_threshold() * 1e3 << " mm plus eps_v x the time under gravity ("
     << p.sim.eps_v * 1e3
     << " mm per second; the trial's verdict). D1/D2 (cm, as the paper's Table "
     << "I) over the grasps each engine holds, by grip's code at each engine's settled grasp. "
     << "Compared: every candidate grip simulates (its initial_penetration refusals are left "
     << "out). " << result.threads << " thread(s), " << fixed_or_dash(result.wall_seconds / 60, 1)
     << " min.\n\n";
  if (result.gripper == "leap") {
    md << "The hand: the LEAP hand's coarse links (8-sided capsules; MuJoCo collides their convex "
          "hulls, which they are), its root welded at the candidate's pose, each joint a "
          "position servo; each finger follows grip's closing path in joint space, at "
       << MujocoSettings{}.approach_speed * 100 << " cm/s until it touches, then at "
       << p.squeeze_speed * 100 << " cm/s until its normal force with the object reaches "
       << p.grip_force << " N less the tolerance, then held there.\n\n";
  }
  if (result.gripper == "fin-ray") {
    md << "The fin-ray: grip's production fingers (the same tets, E, nu, density, Rayleigh "
          "damping and pad friction) as MuJoCo flexes under its discrete integrator, moved by a "
          "trilinear field over "
       << s.flex_cells[0] << " x " << s.flex_cells[1] << " x " << s.flex_cells[2]
       << " cells of each finger's box, their mount nodes held to the jaws by connect "
          "constraints; contacts solref "
       << s.flex_contact_time_constant << " s, solimp " << s.flex_contact_impedance
       << " (bench/peer/mujoco_trial.hpp)"
       << (result.mujoco_ipc ? "; MuJoCo's IPC contact mode enabled (--mujoco-ipc)" : "")
       << ".\n\n";
  }
  write_peer_table(md, tallies);
  md << "\nVerdicts over the compared candidates:\n\n| gripper | category | refused by grip | "
        "grip | MuJoCo |\n|---|---|---:|---|---|\n";
  for (const PeerTally& t : tallies) {
    md << "| " << t.gripper << " | " << t.category << " | " << t.refused << " | "
       << verdict_counts(t.grip.verdicts) << " | " << verdict_counts(t.mujoco.verdicts) << " |\n";
  }
  for (const std::string& s : result.shortfalls) md << "\nShortfall: " << s << "\n";
  for (const std::string& v : result.vtk) md << "\nVTK: " << v << "\n";
  std::ofstream csv(out / (stem + ".csv"));
  csv << "gripper,category,seed,candidate,grip_verdict,mujoco_verdict,grip_d1_mm,mujoco_d1_mm,"
         "grip_d2_mm,mujoco_d2_mm,grip_slip_mm,mujoco_slip_mm,mujoco_penetration_mm,"
         "mujoco_inverted_tets,grip_cpu_s,mujoco_cpu_s,mujoco_compile_cpu_s,mujoco_message\n";
  for (const PeerTrial& t : result.trials) {
    csv << t.gripper << ',' << t.category << ',' << t.seed << ',' << t.candidate << ','
        << t.grip_verdict << ',' << t.mujoco_verdict << ',' << fixed_or_dash(t.grip_d1 * 1e3, 4)
        << ',' << fixed_or_dash(t.mujoco_d1 * 1e3, 4) << ',' << fixed_or_dash(t.grip_d2 * 1e3, 4)
        << ',' << fixed_or_dash(t.mujoco_d2 * 1e3, 4) << ',' << fixed_or_dash(t.grip_slip * 1e3, 4)
        << ',' << fixed_or_dash(t.mujoco_slip * 1e3, 4) << ','
        << fixed_or_dash(t.mujoco_penetration * 1e3, 4) << ',' << t.mujoco_inverted_tets << ','
        << fixed_or_dash(t.grip_cpu_seconds, 4) << ',' << fixed_or_dash(t.mujoco_cpu_seconds, 4)
        << ',' << fixed_or_dash(t.mujoco_compile_cpu_seconds, 4) << ",\"" << t.mujoco_message
        << "\"\n";
  }
}

void write_peer_json_line(std::ostream& out, const PeerResult& result,
                          const std::vector<PeerTally>& tallies) {
  const auto engine = [](const PeerEngineStats& s) {
    return nlohmann::ordered_json{{"held", s.held},
                                  {"d1_mean", s.d1_mean},
                                  {"d1_median", s.d1_median},
                                  {"d2_mean", s.d2_mean},
                                  {"d2_median", s.d2_median},
                                  {"cpu_mean", s.cpu_mean},
                                  {"cpu_median", s.cpu_median}};
  };
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const PeerTally& t : tallies) {
    rows.push_back({{"gripper", t.gripper},
                    {"category", t.category},
                    {"candidates", t.candidates},
                    {"refused_by_grip", t.refused},
                    {"compared", t.compared},
                    {"same_verdict", t.agree},
                    {"mujoco_holds_grip_drops", t.mujoco_only},
                    {"grip_holds_mujoco_drops", t.grip_only},
                    {"grip", engine(t.grip)},
                    {"mujoco", engine(t.mujoco)},
                    {"mujoco_penetration_median", t.mujoco_penetration_median},
                    {"mujoco_penetration_max", t.mujoco_penetration_max},
                    {"mujoco_inverting", t.mujoco_inverting}});
  }
  const nlohmann::ordered_json root = {{"benchmark", "peer"},
                                       {"mujoco", result.mujoco_version},
                                       {"mujoco_ipc", result.mujoco_ipc},
                                       {"threads", result.threads},
                                       {"wall_seconds", result.wall_seconds},
                                       {"rows", std::move(rows)}};
  out << json::text(root, "%.6g") << '\n' << std::flush;
}

}  // namespace grip::bench
