#include "src/scene/scene_run.hpp"

#include <chrono>
#include <cstdint>
#include <memory>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <nlohmann/json.hpp>

#include "solver/batch/engines.hpp"
#include "src/json/json_text.hpp"
#include "src/scene/invariants.hpp"

namespace grip::scene {

BatchReport run_scenes(const std::vector<SceneFile>& files, const std::vector<std::string>& names,
                       bool trace, int threads, solver::EngineDevice device) {
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<solver::Engine> engine = solver::make_engine(device, threads);
  solver::Engine& batch = *engine;
  BatchReport report;
  report.threads = batch.threads();
  report.scenes.resize(files.size());
  std::vector<std::int64_t> steps(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    batch.add(solver::Model::build(files[i].scene));
    report.scenes[i].scene = names.at(i);
    steps[i] = files[i].steps();
    if (steps[i] <= 0) batch.retire(static_cast<int>(i));
  }
  tbb::task_arena checks(batch.threads());
  // A body wholly inside another is an intersecting start, as crossing surfaces are.
  checks.execute([&] {
    tbb::parallel_for(std::size_t{0}, files.size(), [&](std::size_t i) {
      if (steps[i] <= 0) return;
      const auto contained = find_contained_body(batch.environment(static_cast<int>(i)));
      if (!contained) return;
      SceneReport& r = report.scenes[i];
      r.ok = false;
      r.intersection_free = false;
      r.failure = "intersecting start: body '" + files[i].scene.bodies[contained->first].name +
                  "' lies wholly inside body '" + files[i].scene.bodies[contained->second].name +
                  "'; move it out";
    });
  });
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (!report.scenes[i].ok) batch.retire(static_cast<int>(i));
  }
  std::vector<int> stepped;
  while (batch.any_active()) {
    stepped.clear();
    for (int i = 0; i < batch.size(); ++i) {
      if (batch.active(i)) stepped.push_back(i);
    }
    batch.step();
    // The exact intersection check costs more than a step of a small scene: in parallel too.
    checks.execute([&] {
      tbb::parallel_for(std::size_t{0}, stepped.size(), [&](std::size_t k) {
        const int i = stepped[k];
        const solver::EnvironmentHandle& env = batch.environment(i);
        SceneReport& r = report.scenes[i];
        if (env.failed()) {
          r.ok = false;
          r.failure = env.failure();
          return;
        }
        ++r.steps;
        const solver::StepDiagnostics& d = env.last_step();
        r.min_distance = std::min(r.min_distance, d.min_distance);
        r.min_volume_ratio = std::min(r.min_volume_ratio, d.min_volume_ratio);
        r.newton_total += d.newton_iterations;
        r.newton_max_per_step = std::max(r.newton_max_per_step, d.newton_iterations);
        if (count_intersections(env) != 0) r.intersection_free = false;
        if (trace) {
          TraceRow row{env.time(), {}};
          for (int b = 0; b < static_cast<int>(env.model().bodies().size()); ++b) {
            row.com.push_back(env.center_of_mass(b));
          }
          r.trace.push_back(std::move(row));
        }
      });
    });
    for (int i : stepped) {
      if (report.scenes[i].steps == steps[i]) batch.retire(i);
    }
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    const solver::EnvironmentHandle& env = batch.environment(static_cast<int>(i));
    for (int b = 0; b < static_cast<int>(files[i].scene.bodies.size()); ++b) {
      report.scenes[i].bodies.push_back({files[i].scene.bodies[b].name, env.center_of_mass(b),
                                         env.center_of_mass_velocity(b), env.rotation(b)});
    }
  }
  report.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

namespace {

nlohmann::ordered_json vector_json(const Eigen::Vector3d& v) {
  return nlohmann::ordered_json::array({v[0], v[1], v[2]});
}

nlohmann::ordered_json scene_json(const SceneReport& report, bool trace) {
  nlohmann::ordered_json bodies = nlohmann::ordered_json::object();
  for (const BodyReport& body : report.bodies) {
    nlohmann::ordered_json rotation = nlohmann::ordered_json::array();
    for (int r = 0; r < 3; ++r) rotation.push_back(vector_json(body.rotation.row(r).transpose()));
    bodies[body.name] = {{"com", vector_json(body.com)},
                         {"velocity", vector_json(body.velocity)},
                         {"rotation", std::move(rotation)}};
  }
  nlohmann::ordered_json scene = {
      {"scene", report.scene},
      {"status", report.ok ? "ok" : "failed"},
      {"failure", report.ok ? nlohmann::ordered_json() : nlohmann::ordered_json(report.failure)},
      {"steps", report.steps},
      {"bodies", std::move(bodies)},
      {"min_distance", report.min_distance},  // null when no contact ever came within d_hat
      {"min_volume_ratio", report.min_volume_ratio},
      {"intersection_free", report.intersection_free},
      {"newton_iterations",
       {{"total", report.newton_total}, {"max_per_step", report.newton_max_per_step}}}};
  if (trace) {
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const TraceRow& row : report.trace) {
      nlohmann::ordered_json com = nlohmann::ordered_json::object();
      for (std::size_t b = 0; b < row.com.size(); ++b) {
        com[report.bodies[b].name] = vector_json(row.com[b]);
      }
      rows.push_back({{"t", row.time}, {"com", std::move(com)}});
    }
    scene["trace"] = std::move(rows);
  }
  return scene;
}

}  // namespace

void write_json(std::ostream& out, const BatchReport& report, bool trace) {
  nlohmann::ordered_json scenes = nlohmann::ordered_json::array();
  for (const SceneReport& scene : report.scenes) scenes.push_back(scene_json(scene, trace));
  const nlohmann::ordered_json root = {{"threads", report.threads},
                                       {"wall_seconds", report.wall_seconds},
                                       {"scenes", std::move(scenes)}};
  // A line per top-level key, scene key, body and trace row; every double exactly (17 digits).
  out << json::text(root, "%.17g",
                    {{"", 0},
                     {"/scenes", 0},
                     {"/scenes/*", 2},
                     {"/scenes/*/bodies", 4},
                     {"/scenes/*/trace", 4}})
      << '\n';
}

}  // namespace grip::scene
