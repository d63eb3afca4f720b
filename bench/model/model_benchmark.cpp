#include "bench/model/model_benchmark.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <iomanip>
#include <random>

#include "bench/common/subprocess.hpp"
#include "solver/batch/batch.hpp"

namespace grip::bench {
namespace {

// What one run of a variant gave: one result per environment (one, but for the batch).
struct VariantRun {
  double wall_s = 0.0;
  double cpu_s = 0.0;
  long iterations = 0;
  int dofs = 0;
  double frozen_fraction = std::numeric_limits<double>::quiet_NaN();
  std::vector<SqueezeResult> results;
};

struct Variant {
  std::string model;
  std::function<VariantRun()> run;
};

struct Comparison {
  std::string name;
  Variant lean;
  Variant full;
};

VariantRun single(const SqueezeOptions& options, const SqueezeScene& scene,
                  bool friction_terms_at_zero_mu = false) {
  VariantRun run;
  run.results.push_back(
      run_squeeze(options, scene, Eigen::Isometry3d::Identity(), friction_terms_at_zero_mu));
  run.wall_s = run.results[0].wall_s;
  run.cpu_s = run.results[0].cpu_s;
  run.iterations = run.results[0].newton_iterations;
  run.dofs = run.results[0].free_dofs;
  return run;
}

// One environment of the batch comparison: its scene and where its cube starts.
struct BatchMember {
  const SqueezeOptions* options;
  const SqueezeScene* scene;
  Eigen::Isometry3d placement;
};

// The members in one batch, freezing converged environments or keeping all iterating until
// every one has converged.
VariantRun batched(const std::vector<BatchMember>& members, int threads, bool freeze) {
  solver::Batch batch(threads);
  batch.set_policy({.freeze_converged = freeze});
  for (const BatchMember& member : members) {
    batch.environment(batch.add(member.scene->model)).place(0, member.placement);
  }
  VariantRun run;
  long frozen = 0;
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  std::vector<SqueezeProgress> progress(members.size());
  while (batch.any_active()) {
    for (int e = 0; e < batch.size(); ++e) {
      if (batch.active(e) && !next_squeeze_step(*members[e].options, *members[e].scene,
                                                batch.environment(e), progress[e])) {
        batch.retire(e);
      }
    }
    if (!batch.any_active()) break;
    const solver::BatchStepReport report = batch.step();
    run.iterations += report.iterations;
    frozen += report.frozen;
  }
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  run.frozen_fraction = static_cast<double>(frozen) / static_cast<double>(run.iterations + frozen);
  for (int e = 0; e < batch.size(); ++e) {
    run.results.push_back(squeeze_result(*members[e].scene, batch.environment(e)));
    run.dofs += run.results.back().free_dofs;
  }
  return run;
}

// Each cube turned about the closing axis by up to 10 degrees (its faces stay parallel to the
// pads), moved sideways by up to 2 mm and raised by 3.5 to 5.5 mm (clear of a floor however it
// is turned), so that the environments' contacts differ and they converge at different
// iterations.
std::vector<Eigen::Isometry3d> placements(int count) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Eigen::Isometry3d> result;
  for (int e = 0; e < count; ++e) {
    Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();
    placement.translate(Eigen::Vector3d(0.0, 2e-3 * unit(rng), 4.5e-3 + 1e-3 * unit(rng)));
    placement.rotate(Eigen::AngleAxisd(10.0 * M_PI / 180.0 * unit(rng), Eigen::Vector3d::UnitX()));
    result.push_back(placement);
  }
  return result;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::string failure_of(const std::string& variant, const VariantRun& run) {
  for (std::size_t e = 0; e < run.results.size(); ++e) {
    if (run.results[e].failed) {
      return variant + " (environment " + std::to_string(e) + "): " + run.results[e].failure;
    }
  }
  return {};
}

bool same_end(const VariantRun& a, const VariantRun& b) {
  for (std::size_t e = 0; e < a.results.size(); ++e) {
    if (a.results[e].dofs != b.results[e].dofs) return false;
  }
  return a.iterations == b.iterations;
}

// A CSV field, quoted when it holds a comma or a quote.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string micrometres(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", metres * 1e6);
  return text;
}

}  // namespace

std::vector<ModelComparison> run_model_benchmark(const ModelBenchmarkOptions& options,
                                                 std::ostream& log) {
  const SqueezeOptions lean = options.scene;
  SqueezeOptions fem_object = lean;
  fem_object.fem_object = true;
  SqueezeOptions fem_fingers = lean;
  fem_fingers.fem_fingers = true;
  SqueezeOptions frictionless = lean;
  frictionless.friction = 0.0;
  frictionless.ground = true;  // without friction the pads cannot hold the cube up

  const SqueezeScene lean_scene = make_squeeze_scene(lean);
  const SqueezeScene fem_object_scene = make_squeeze_scene(fem_object);
  const SqueezeScene fem_fingers_scene = make_squeeze_scene(fem_fingers);
  const SqueezeScene frictionless_scene = make_squeeze_scene(frictionless);
  // The batch mixes cubes held by friction (a few Newton iterations per step) with frictionless
  // cubes sliding out between the pads (a dozen), as a batch of trials mixes easy and hard ones.
  std::vector<BatchMember> members;
  for (const Eigen::Isometry3d& placement : placements(options.batch_envs)) {
    const bool held = members.size() % 2 == 0;
    members.push_back(
        {held ? &lean : &frictionless, held ? &lean_scene : &frictionless_scene, placement});
  }
  char youngs[32];
  std::snprintf(youngs, sizeof youngs, "%.0e", lean.stiff_youngs);

  const std::vector<Comparison> comparisons{
      {"rigid object",
       {"affine cube (12 DOFs)", [&] { return single(lean, lean_scene); }},
       {std::string("FEM cube, E = ") + youngs + " Pa",
        [&] { return single(fem_object, fem_object_scene); }}},
      {"kinematic fingers",
       {"kinematic pads", [&] { return single(lean, lean_scene); }},
       {std::string("FEM pads (E = ") + youngs + " Pa) pinned to kinematic jaws",
        [&] { return single(fem_fingers, fem_fingers_scene); }}},
      {"frozen environments",
       {"batch of " + std::to_string(options.batch_envs) +
            " (half of them frictionless), converged ones frozen",
        [&] { return batched(members, options.threads, true); }},
       {"all iterate until the slowest converges",
        [&] { return batched(members, options.threads, false); }}},
      {"no friction at mu = 0",
       {"mu = 0 pairs without friction terms",
        [&] { return single(frictionless, frictionless_scene); }},
       {"friction terms assembled at mu = 0",
        [&] { return single(frictionless, frictionless_scene, true); }}},
  };

  std::vector<ModelComparison> rows(comparisons.size());
  std::vector<VariantRun> first_lean(comparisons.size()), first_full(comparisons.size());
  for (int r = 0; r < options.repeats; ++r) {
    for (std::size_t c = 0; c < comparisons.size(); ++c) {
      ModelComparison& row = rows[c];
      // Interleaved, and the order turned round every other repeat, so that the machine's
      // drifts fall on both variants alike.
      for (int k = 0; k < 2; ++k) {
        const bool is_lean = (k == 0) == (r % 2 == 0);
        const Variant& variant = is_lean ? comparisons[c].lean : comparisons[c].full;
        const VariantRun run = variant.run();
        log << "  repeat " << r + 1 << "/" << options.repeats << "  " << comparisons[c].name << ", "
            << (is_lean ? "lean" : "full") << ": " << std::fixed << std::setprecision(3)
            << run.wall_s << " s (CPU " << run.cpu_s << " s), " << run.iterations
            << " Newton iterations, closing force " << std::setprecision(2)
            << run.results[0].closing_force << " N, cube centre " << std::setprecision(4)
            << 1e3 * run.results[0].center.transpose() << " mm" << std::defaultfloat << std::endl;
        (is_lean ? row.lean_runs : row.full_runs).push_back(run.wall_s);
        (is_lean ? row.lean_cpu_runs : row.full_cpu_runs).push_back(run.cpu_s);
        VariantRun& first = is_lean ? first_lean[c] : first_full[c];
        if (r == 0) {
          first = run;
        } else {
          row.reproducible = row.reproducible && same_end(first, run);
        }
      }
    }
  }

  for (std::size_t c = 0; c < comparisons.size(); ++c) {
    ModelComparison& row = rows[c];
    const VariantRun& lean_run = first_lean[c];
    const VariantRun& full_run = first_full[c];
    row.name = comparisons[c].name;
    row.lean = comparisons[c].lean.model;
    row.full = comparisons[c].full.model;
    row.lean_dofs = lean_run.dofs;
    row.full_dofs = full_run.dofs;
    row.lean_iterations = lean_run.iterations;
    row.full_iterations = full_run.iterations;
    row.lean_s = median(row.lean_runs);
    row.full_s = median(row.full_runs);
    row.lean_cpu_s = median(row.lean_cpu_runs);
    row.full_cpu_s = median(row.full_cpu_runs);
    row.frozen_fraction = lean_run.frozen_fraction;
    row.failure = failure_of("lean", lean_run);
    if (row.failure.empty()) row.failure = failure_of("full", full_run);
    for (std::size_t e = 0; e < lean_run.results.size(); ++e) {
      const SqueezeError error = squeeze_error(lean_run.results[e], full_run.results[e]);
      row.error.center_m = std::max(row.error.center_m, error.center_m);
      row.error.rotation_rad = std::max(row.error.rotation_rad, error.rotation_rad);
      row.error.vertex_m = std::max(row.error.vertex_m, error.vertex_m);
      row.error.force_relative = std::max(row.error.force_relative, error.force_relative);
      row.vertex_errors_m.push_back(error.vertex_m);
    }
  }
  return rows;
}

void write_model_table(std::ostream& out, const std::vector<ModelComparison>& comparisons) {
  out << "| comparison | lean model | full model | DOFs lean / full | Newton its lean / full "
         "| time lean (s) | time full (s) | full / lean | CPU lean / full (s) | CPU full / lean "
         "| centre error (um) | rotation error (mrad) | max vertex error (um) | closing force "
         "error |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ModelComparison& c : comparisons) {
    char figures[512];
    std::snprintf(figures, sizeof figures,
                  "| %d / %d | %ld / %ld | %.3f | %.3f | %.2fx | %.3f / %.3f | %.2fx | %s | %.3g | "
                  "%s | %.2g%% |",
                  c.lean_dofs, c.full_dofs, c.lean_iterations, c.full_iterations, c.lean_s,
                  c.full_s, c.full_s / c.lean_s, c.lean_cpu_s, c.full_cpu_s,
                  c.full_cpu_s / c.lean_cpu_s, micrometres(c.error.center_m).c_str(),
                  c.error.rotation_rad * 1e3, micrometres(c.error.vertex_m).c_str(),
                  100.0 * c.error.force_relative);
    out << "| " << c.name << " | " << c.lean << " | " << c.full << " " << figures << "\n";
  }
  for (const ModelComparison& c : comparisons) {
    if (std::isfinite(c.frozen_fraction)) {
      out << "\n"
          << c.name << ": " << std::fixed << std::setprecision(1) << 100.0 * c.frozen_fraction
          << std::defaultfloat
          << "% of the frozen batch's environment-rounds were spent frozen. Max vertex error "
             "per environment (um):";
      for (const double error : c.vertex_errors_m) out << " " << micrometres(error);
      out << "\n";
    }
    if (!c.failure.empty()) out << "\n" << c.name << ": FAILED " << c.failure << "\n";
    if (!c.reproducible) out << "\n" << c.name << ": repeats ended in different states\n";
  }
}

void write_model_csv(std::ostream& out, const std::vector<ModelComparison>& comparisons) {
  out << "comparison,lean,full,lean_dofs,full_dofs,lean_iterations,full_iterations,lean_s,full_s,"
         "lean_cpu_s,full_cpu_s,center_error_m,rotation_error_rad,vertex_error_m,force_error_"
         "relative,frozen_fraction,"
         "failed,lean_runs_s,full_runs_s,lean_cpu_runs_s,full_cpu_runs_s\n";
  auto runs = [](const std::vector<double>& values) {
    std::string text;
    for (const double v : values) {
      if (!text.empty()) text += ' ';
      text += std::to_string(v);
    }
    return text;
  };
  out << std::setprecision(6);
  for (const ModelComparison& c : comparisons) {
    out << csv_field(c.name) << "," << csv_field(c.lean) << "," << csv_field(c.full) << ","
        << c.lean_dofs << "," << c.full_dofs << "," << c.lean_iterations << "," << c.full_iterations
        << "," << c.lean_s << "," << c.full_s << "," << c.lean_cpu_s << "," << c.full_cpu_s << ","
        << c.error.center_m << "," << c.error.rotation_rad << "," << c.error.vertex_m << ","
        << c.error.force_relative << ",";
    if (std::isfinite(c.frozen_fraction)) out << c.frozen_fraction;
    out << "," << (c.failure.empty() ? 0 : 1) << "," << runs(c.lean_runs) << ","
        << runs(c.full_runs) << "," << runs(c.lean_cpu_runs) << "," << runs(c.full_cpu_runs)
        << "\n";
  }
}

bool write_model_outputs(const std::filesystem::path& out,
                         const std::vector<ModelComparison>& comparisons,
                         const ModelBenchmarkOptions& options) {
  std::filesystem::create_directories(out);
  {
    std::ofstream md(out / "model.md");
    md << "`grip bench model --repeats " << options.repeats << " --threads " << options.threads
       << "`: medians of " << options.repeats
       << " interleaved runs per variant on one thread, wall time and the process's CPU time "
          "(on a shared machine the wall time carries the load of other processes; the CPU time "
          "is steadier). "
          "Errors: the lean model's end state against the full one's (the cube's centre of mass "
          "and rotation, the largest distance between matching surface vertices, the pads' "
          "normal force on it); the batch row gives the largest over its environments.\n\n";
    write_model_table(md, comparisons);
  }
  {
    std::ofstream csv(out / "model.csv");
    write_model_csv(csv, comparisons);
  }
  return plot("bench/model/plot_model.py",
              {(out / "model.csv").string(), (out / "model.png").string()}, out);
}

}  // namespace grip::bench
