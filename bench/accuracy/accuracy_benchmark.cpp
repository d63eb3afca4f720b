#include "bench/accuracy/accuracy_benchmark.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <stdexcept>

#include "bench/accuracy/accuracy_scenes.hpp"
#include "bench/accuracy/pareto_front.hpp"
#include "bench/common/subprocess.hpp"

namespace grip::bench {
namespace {

namespace fs = std::filesystem;

// One swept setting: its values (the default among them) and how a value enters the protocol.
// The mesh sweep's values belong to the scene.
struct Sweep {
  std::string name;
  std::vector<double> values;
  std::function<void(trial::TrialParameters&, double)> apply;
};

const std::vector<Sweep>& sweeps() {
  static const std::vector<Sweep> all = {
      {"dt", {0.005, 0.01, 0.02, 0.04}, [](trial::TrialParameters& p, double v) { p.sim.dt = v; }},
      {"newton_tol",
       {1e-2, 1e-3, 1e-4},
       [](trial::TrialParameters& p, double v) { p.sim.newton_tol = v; }},
      {"d_hat", {5e-4, 1e-3, 2e-3}, [](trial::TrialParameters& p, double v) { p.sim.d_hat = v; }},
      {"kappa", {1e6, 3e6, 1e7}, [](trial::TrialParameters& p, double v) { p.sim.kappa = v; }},
      {"eps_v", {3e-4, 1e-3, 1e-2}, [](trial::TrialParameters& p, double v) { p.sim.eps_v = v; }},
      {"friction_lag_iterations",
       {1, 2},
       [](trial::TrialParameters& p, double v) {
         p.sim.friction_lag_iterations = static_cast<int>(std::lround(v));
       }},
      {"mesh", {}, nullptr},
  };
  return all;
}

// The tight reference: the default model (d_hat, kappa, eps_v, mesh) with tight numerics. The
// mesh sweep is instead compared with its finest mesh at the default numerics, so that its
// error is the discretization's alone.
trial::TrialParameters reference_parameters(trial::TrialParameters p) {
  p.sim.dt /= 4;
  // newton_velocity_tol stays at its default: far below it, Newton stalls before either test
  // passes (the residual no longer falls) and the step fails at the iteration limit.
  p.sim.newton_tol = 1e-5;
  p.sim.max_newton_iters = 500;
  p.sim.friction_lag_iterations = 2;
  return p;
}

// One distinct setting of a scene that is run (a sweep's default is run once, for all sweeps).
struct Point {
  trial::TrialParameters parameters;
  double mesh = 0;
  std::string label;
  std::vector<SceneRun> repeats;
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

bool same_settings(const Point& a, const trial::TrialParameters& p, double mesh) {
  const solver::SimParameters &x = a.parameters.sim, &y = p.sim;
  return a.mesh == mesh && x.dt == y.dt && x.newton_tol == y.newton_tol && x.d_hat == y.d_hat &&
         x.kappa == y.kappa && x.eps_v == y.eps_v &&
         x.friction_lag_iterations == y.friction_lag_iterations;
}

std::string number(double v) { return fmt::format("{:g}", v); }

// Millimetres (or milliradians) with three significant digits; "n/a" for NaN.
std::string milli(double v) { return std::isnan(v) ? "n/a" : fmt::format("{:.3g}", 1e3 * v); }

void write_csv(const fs::path& path, const std::vector<AccuracyRow>& rows) {
  std::ofstream csv(path);
  csv << "scene,sweep,value,default,seconds,cpu_seconds,newton_iterations,steps,held,candidates,"
         "translation,rotation,slip,vertices,agreeing,sweep_front,scene_front,runs\n";
  for (const AccuracyRow& r : rows) {
    std::string runs;
    for (double s : r.runs) {
      if (!runs.empty()) runs += ';';
      runs += fmt::format("{:.4f}", s);
    }
    csv << r.scene << ',' << r.sweep << ',' << number(r.value) << ',' << r.is_default << ','
        << fmt::format("{:.4f}", r.seconds) << ',' << fmt::format("{:.4f}", r.cpu_seconds) << ','
        << r.newton_iterations << ',' << r.steps << ',' << r.held << ',' << r.error.candidates
        << ',' << fmt::format("{:.6g}", r.error.translation) << ','
        << fmt::format("{:.6g}", r.error.rotation) << ',' << fmt::format("{:.6g}", r.error.slip)
        << ',' << fmt::format("{:.6g}", r.error.vertices) << ',' << r.error.agreeing << ','
        << r.on_sweep_front << ',' << r.on_scene_front << ',' << runs << '\n';
  }
}

void write_markdown(const fs::path& path, const std::vector<AccuracyRow>& rows,
                    const std::vector<AccuracyScene>& scenes, const AccuracyOptions& o) {
  std::ofstream md(path);
  md << "Work-precision of the solver's settings (`grip bench accuracy`). Wall and CPU time "
        "(the process's, over all threads): median of "
     << o.repeats << " run(s) per setting on "
     << (o.threads ? std::to_string(o.threads) + " thread(s)" : std::string("all cores"))
     << ", on a shared, noisy machine; the Pareto fronts use the CPU time, which other "
        "processes' load moves far less. Errors are means over the scene's candidates "
        "against the reference run; verdicts count the candidates whose held/not held agrees "
        "with the reference's (judged by the reference's threshold: 1 mm plus eps_v x the time "
        "under gravity).\n\n"
     << accuracy_settings_text() << "\n\nScenes:\n\n";
  for (const AccuracyScene& s : scenes) {
    md << "- **" << s.name << "**: " << s.setup << "; mesh sweep: " << s.mesh_setting << ".\n";
  }
  md << "- **bimanual**: not run; there is no bimanual trial scene in the code.\n";
  for (const AccuracyScene& s : scenes) {
    md << "\n### " << s.name << "\n\n"
       << "| sweep | value | wall (s) | CPU (s) | Newton it. | steps | pose (mm) | rotation (mrad) "
          "| "
          "slip (mm) | vertices (mm) | verdicts | front (sweep / scene) |\n"
       << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (const AccuracyRow& r : rows) {
      if (r.scene != s.name) continue;
      const bool reference = r.sweep == "reference";
      md << "| " << r.sweep << " | " << (reference ? "" : number(r.value))
         << (r.is_default ? " (default)" : "") << " | " << fmt::format("{:.2f}", r.seconds) << " | "
         << fmt::format("{:.2f}", r.cpu_seconds) << " | " << r.newton_iterations << " | " << r.steps
         << " | " << (reference ? "0" : milli(r.error.translation)) << " | "
         << (reference ? "0" : milli(r.error.rotation)) << " | "
         << (reference ? "0" : milli(r.error.slip)) << " | "
         << (reference ? "0" : milli(r.error.vertices)) << " | " << r.error.agreeing << "/"
         << r.error.candidates << " | "
         << (reference ? ""
                       : std::string(r.on_sweep_front ? "yes" : "no") + " / " +
                             (r.sweep == "mesh"  ? "-"
                              : r.on_scene_front ? "yes"
                                                 : "no"))
         << " |\n";
    }
  }
  md << "\n### Defaults on the Pareto front of (CPU time, pose error)\n\n| scene |";
  std::vector<std::string> swept;
  for (const AccuracyRow& r : rows) {
    if (r.sweep != "reference" && std::find(swept.begin(), swept.end(), r.sweep) == swept.end()) {
      swept.push_back(r.sweep);
    }
  }
  for (const std::string& s : swept) md << ' ' << s << " |";
  md << "\n| --- |";
  for (std::size_t k = 0; k < swept.size(); ++k) md << " --- |";
  md << '\n';
  for (const AccuracyScene& s : scenes) {
    md << "| " << s.name << " |";
    for (const std::string& sweep : swept) {
      const auto it = std::find_if(rows.begin(), rows.end(), [&](const AccuracyRow& r) {
        return r.scene == s.name && r.sweep == sweep && r.is_default;
      });
      md << ' ' << (it == rows.end() ? "-" : it->on_sweep_front ? "yes" : "no") << " |";
    }
    md << '\n';
  }
}

}  // namespace

std::vector<std::string> accuracy_sweep_names() {
  std::vector<std::string> names;
  for (const Sweep& s : sweeps()) names.push_back(s.name);
  return names;
}

std::string accuracy_settings_text() {
  std::string text =
      "Reference (per scene): the default model (d_hat, kappa, eps_v, mesh) with tight "
      "numerics: dt / 4, newton_tol 1e-5 (a step also ends once Newton changes no velocity by "
      "more than newton_velocity_tol, 1e-6 m/s, as by default), 2 friction lag iterations, up "
      "to 500 Newton iterations a step. The mesh sweep is compared with its own finest mesh at "
      "the default numerics instead (discretization error alone). Sweeps, one "
      "setting at a time around the defaults:";
  for (const Sweep& s : sweeps()) {
    if (s.values.empty()) {
      text += " mesh (per scene: fin-ray tet layers, soft object tet cell, cylinder sides).";
      continue;
    }
    text += " " + s.name + " {";
    for (std::size_t k = 0; k < s.values.size(); ++k) {
      text += (k ? ", " : "") + number(s.values[k]);
    }
    text += "};";
  }
  return text;
}

std::vector<AccuracyRow> run_accuracy(const AccuracyOptions& options) {
  if (options.repeats < 1) {
    throw std::invalid_argument("grip bench accuracy: give at least one repeat");
  }
  std::vector<const Sweep*> chosen;
  for (const std::string& name : options.sweeps.empty() ? accuracy_sweep_names() : options.sweeps) {
    const auto it = std::find_if(sweeps().begin(), sweeps().end(),
                                 [&](const Sweep& s) { return s.name == name; });
    if (it == sweeps().end()) {
      std::string known;
      for (const std::string& n : accuracy_sweep_names()) known += (known.empty() ? "" : ", ") + n;
      throw std::invalid_argument("grip bench accuracy: unknown sweep '" + name + "' (" + known +
                                  ")");
    }
    chosen.push_back(&*it);
  }
  const std::vector<AccuracyScene> scenes =
      standard_scenes(options.scenes.empty() ? standard_scene_names() : options.scenes);
  fs::create_directories(options.out);

  std::vector<AccuracyRow> rows;
  for (const AccuracyScene& scene : scenes) {
    // The distinct settings to run: the reference first, then every sweep's values.
    std::vector<Point> points;
    const auto point = [&](const trial::TrialParameters& p, double mesh, const std::string& label) {
      for (std::size_t k = 0; k < points.size(); ++k) {
        if (same_settings(points[k], p, mesh)) return k;
      }
      points.push_back({p, mesh, label, {}});
      return points.size() - 1;
    };
    point(reference_parameters(scene.parameters), scene.default_mesh, "reference");
    struct Planned {
      const Sweep* sweep;
      double value;
      bool is_default;
      std::size_t point;
    };
    std::vector<Planned> planned;
    for (const Sweep* sweep : chosen) {
      const bool mesh = sweep->values.empty();
      for (double value : mesh ? scene.mesh_values : sweep->values) {
        trial::TrialParameters p = scene.parameters;
        if (!mesh) sweep->apply(p, value);
        const bool is_default = mesh ? value == scene.default_mesh
                                     : same_settings(Point{scene.parameters, 0, "", {}}, p, 0);
        planned.push_back(
            {sweep, value, is_default,
             point(p, mesh ? value : scene.default_mesh, sweep->name + " " + number(value))});
      }
    }
    // Repeats interleave the settings, so that the machine's noise falls on all of them alike.
    for (int repeat = 0; repeat < options.repeats; ++repeat) {
      for (Point& p : points) {
        p.repeats.push_back(scene.run(p.parameters, p.mesh, options.threads));
        std::uint64_t iterations = 0;
        std::string verdicts;
        for (const trial::TrialOutcome& o : p.repeats.back().outcomes) {
          iterations += o.result.record.newton.iterations;
          verdicts += fmt::format(" {}", io::to_string(o.result.record.failure));
        }
        spdlog::info("{}: {} in {:.2f} s, {} Newton iterations, failures:{} (repeat {})",
                     scene.name, p.label, p.repeats.back().seconds, iterations, verdicts,
                     repeat + 1);
      }
    }

    const trial::TrialParameters& judge = scene.parameters;
    const int frames = scene.parameters.validation_frames + 1;
    const auto measured = [&](AccuracyRow& row, const Point& p) {
      std::vector<double> cpu;
      for (const SceneRun& run : p.repeats) {
        row.runs.push_back(run.seconds);
        cpu.push_back(run.cpu_seconds);
      }
      row.seconds = median(row.runs);
      row.cpu_seconds = median(cpu);
      for (const trial::TrialOutcome& o : p.repeats.front().outcomes) {
        row.newton_iterations += o.result.record.newton.iterations;
        row.steps += o.result.record.newton.steps;
        row.held += held(o.result.record, judge);
      }
    };
    const Point& reference = points.front();
    AccuracyRow reference_row;
    reference_row.scene = scene.name;
    reference_row.sweep = "reference";
    measured(reference_row, reference);
    reference_row.error = run_error(reference.repeats.front().outcomes,
                                    reference.repeats.front().outcomes, frames, judge);
    const std::size_t first = rows.size();
    rows.push_back(reference_row);
    for (const Planned& plan : planned) {
      AccuracyRow row;
      row.scene = scene.name;
      row.sweep = plan.sweep->name;
      row.value = plan.value;
      row.is_default = plan.is_default;
      measured(row, points[plan.point]);
      const bool mesh = plan.sweep->values.empty();
      // The mesh sweep's reference: its finest mesh (the last value) at the default numerics.
      const Point& against = mesh
                                 ? points[std::find_if(planned.begin(), planned.end(),
                                                       [&](const Planned& q) {
                                                         return q.sweep == plan.sweep &&
                                                                q.value == scene.mesh_values.back();
                                                       })
                                              ->point]
                                 : reference;
      row.error = run_error(points[plan.point].repeats.front().outcomes,
                            against.repeats.front().outcomes, frames, judge);
      rows.push_back(row);
    }
    // Fronts: per sweep, and over every numerical setting of the scene (each point once).
    for (const Sweep* sweep : chosen) {
      std::vector<std::size_t> mine;
      std::vector<CostError> costs;
      for (std::size_t k = first + 1; k < rows.size(); ++k) {
        if (rows[k].sweep != sweep->name) continue;
        mine.push_back(k);
        costs.push_back({rows[k].cpu_seconds, rows[k].error.translation});
      }
      const std::vector<bool> front = pareto_front(costs);
      for (std::size_t i = 0; i < mine.size(); ++i) rows[mine[i]].on_sweep_front = front[i];
    }
    std::vector<std::size_t> numerical;
    std::vector<CostError> costs;
    bool default_taken = false;
    for (std::size_t k = first + 1; k < rows.size(); ++k) {
      if (rows[k].sweep == "mesh" || (rows[k].is_default && default_taken)) continue;
      default_taken = default_taken || rows[k].is_default;
      numerical.push_back(k);
      costs.push_back({rows[k].cpu_seconds, rows[k].error.translation});
    }
    const std::vector<bool> front = pareto_front(costs);
    bool default_front = false;
    for (std::size_t i = 0; i < numerical.size(); ++i) {
      rows[numerical[i]].on_scene_front = front[i];
      if (rows[numerical[i]].is_default) default_front = front[i];
    }
    for (std::size_t k = first + 1; k < rows.size(); ++k) {
      if (rows[k].is_default && rows[k].sweep != "mesh") rows[k].on_scene_front = default_front;
    }
  }

  write_csv(options.out / "accuracy.csv", rows);
  write_markdown(options.out / "accuracy.md", rows, scenes, options);
  plot("bench/accuracy/plot_accuracy.py",
       {(options.out / "accuracy.csv").string(), options.out.string()}, options.out);
  return rows;
}

}  // namespace grip::bench
