#include "src/scene/scene_run.hpp"

#include <chrono>
#include <cmath>
#include <iomanip>

#include "solver/environment.hpp"
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

SceneReport run_scene(const SceneFile& file, bool trace) {
  const auto start = std::chrono::steady_clock::now();
  solver::Environment env(solver::Model::build(file.scene));
  SceneReport report;
  const int body_count = static_cast<int>(file.scene.bodies.size());
  const int steps = static_cast<int>(std::llround(file.duration / file.scene.sim.dt));
  for (int s = 0; s < steps; ++s) {
    if (!env.step()) {
      report.ok = false;
      report.failure = env.failure();
      break;
    }
    ++report.steps;
    const solver::StepDiagnostics& d = env.last_step();
    report.min_distance = std::min(report.min_distance, d.min_distance);
    report.min_volume_ratio = std::min(report.min_volume_ratio, d.min_volume_ratio);
    report.newton_total += d.newton_iterations;
    report.newton_max_per_step = std::max(report.newton_max_per_step, d.newton_iterations);
    if (count_intersections(env) != 0) report.intersection_free = false;
    if (trace) {
      TraceRow row{env.time(), {}};
      for (int b = 0; b < body_count; ++b) row.com.push_back(env.center_of_mass(b));
      report.trace.push_back(std::move(row));
    }
  }
  for (int b = 0; b < body_count; ++b) {
    report.bodies.push_back({file.scene.bodies[b].name, env.center_of_mass(b),
                             env.center_of_mass_velocity(b), env.rotation(b)});
  }
  report.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

void write_json(std::ostream& out, const SceneReport& report, bool trace) {
  out << std::setprecision(17);
  out << "{\n  \"status\": " << (report.ok ? "\"ok\"" : "\"failed\"") << ",\n  \"failure\": ";
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
      << ", \"max_per_step\": " << report.newton_max_per_step << "},\n  \"wall_seconds\": ";
  write_number(out, report.wall_seconds);
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
  out << "\n}\n";
}

}  // namespace grip::scene
