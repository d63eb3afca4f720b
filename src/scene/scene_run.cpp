#include "src/scene/scene_run.hpp"

#include <chrono>
#include <cmath>
#include <iomanip>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "solver/batch/batch.hpp"
#include "src/scene/invariants.hpp"

namespace grip::scene {
namespace {

void write_number(std::ostream& out, double value) {
  if (std::isfinite(value)) {
    out << value;
  } else {
    out << "null";  // JSON has no infinity: e.g. no contact ever came within d_hat
  }
}

void write_vector(std::ostream& out, const Eigen::Vector3d& v) {
  out << '[';
  for (int i = 0; i < 3; ++i) {
    if (i) out << ", ";
    write_number(out, v[i]);
  }
  out << ']';
}

void write_string(std::ostream& out, const std::string& s) {
  out << '"';
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out << '\\' << c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out << "\\u" << std::hex << std::setw(4) << std::setfill('0') << int(c) << std::dec;
    } else {
      out << c;
    }
  }
  out << '"';
}

}  // namespace

BatchReport run_scenes(const std::vector<SceneFile>& files, const std::vector<std::string>& names,
                       bool trace, int threads) {
  const auto start = std::chrono::steady_clock::now();
  solver::Batch batch(threads);
  BatchReport report;
  report.threads = batch.threads();
  report.scenes.resize(files.size());
  std::vector<int> steps(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    batch.add(solver::Model::build(files[i].scene));
    report.scenes[i].scene = names.at(i);
    steps[i] = static_cast<int>(std::llround(files[i].duration / files[i].scene.sim.dt));
    if (steps[i] == 0) batch.retire(static_cast<int>(i));
  }
  tbb::task_arena checks(batch.threads());
  std::vector<int> stepped;
  while (batch.any_active()) {
    stepped.clear();
    for (int i = 0; i < batch.size(); ++i) {
      if (batch.active(i)) stepped.push_back(i);
    }
    batch.step();
    // The exact intersection check costs more than a step of a small scene: in parallel too.
    checks.execute([&] { tbb::parallel_for(std::size_t{0}, stepped.size(), [&](std::size_t k) {
      const int i = stepped[k];
      const solver::Environment& env = batch.environment(i);
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
    }); });
    for (int i : stepped) {
      if (report.scenes[i].steps == steps[i]) batch.retire(i);
    }
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    const solver::Environment& env = batch.environment(static_cast<int>(i));
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

void write_scene(std::ostream& out, const SceneReport& report, bool trace) {
  out << "{\n  \"scene\": ";
  write_string(out, report.scene);
  out << ",\n  \"status\": " << (report.ok ? "\"ok\"" : "\"failed\"") << ",\n  \"failure\": ";
  if (report.ok) {
    out << "null";
  } else {
    write_string(out, report.failure);
  }
  out << ",\n  \"steps\": " << report.steps << ",\n  \"bodies\": {";
  for (std::size_t b = 0; b < report.bodies.size(); ++b) {
    const BodyReport& body = report.bodies[b];
    out << (b ? ",\n    " : "\n    ");
    write_string(out, body.name);
    out << ": {\"com\": ";
    write_vector(out, body.com);
    out << ", \"velocity\": ";
    write_vector(out, body.velocity);
    out << ", \"rotation\": [";
    for (int r = 0; r < 3; ++r) {
      if (r) out << ", ";
      write_vector(out, body.rotation.row(r).transpose());
    }
    out << "]}";
  }
  out << "\n  },\n  \"min_distance\": ";
  write_number(out, report.min_distance);
  out << ",\n  \"min_volume_ratio\": ";
  write_number(out, report.min_volume_ratio);
  out << ",\n  \"intersection_free\": " << (report.intersection_free ? "true" : "false")
      << ",\n  \"newton_iterations\": {\"total\": " << report.newton_total
      << ", \"max_per_step\": " << report.newton_max_per_step << "}";
  if (trace) {
    out << ",\n  \"trace\": [";
    for (std::size_t i = 0; i < report.trace.size(); ++i) {
      const TraceRow& row = report.trace[i];
      out << (i ? ",\n    " : "\n    ") << "{\"t\": ";
      write_number(out, row.time);
      out << ", \"com\": {";
      for (std::size_t b = 0; b < row.com.size(); ++b) {
        if (b) out << ", ";
        write_string(out, report.bodies[b].name);
        out << ": ";
        write_vector(out, row.com[b]);
      }
      out << "}}";
    }
    out << "\n  ]";
  }
  out << "\n}";
}

}  // namespace

void write_json(std::ostream& out, const BatchReport& report, bool trace) {
  out << std::setprecision(17);
  out << "{\n\"threads\": " << report.threads << ",\n\"wall_seconds\": ";
  write_number(out, report.wall_seconds);
  out << ",\n\"scenes\": [";
  for (std::size_t i = 0; i < report.scenes.size(); ++i) {
    out << (i ? ",\n" : "\n");
    write_scene(out, report.scenes[i], trace);
  }
  out << "\n]\n}\n";
}

}  // namespace grip::scene
