#include "src/trial/grasp_trial.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "solver/batch/batch.hpp"
#include "src/scene/invariants.hpp"
#include "src/trial/frame_recorder.hpp"

namespace grip::trial {

namespace {

using grippers::Jaw;
constexpr std::array<Jaw, 2> kJaws = {Jaw::kPositive, Jaw::kNegative};

// Gravity directions of the six validation phases, in order.
const std::array<Eigen::Vector3d, 6> kGravityAxes = {
    Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
    -Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitZ()};

enum class Phase { kClosing, kSettling, kGravity, kDone };

// One candidate's progress through the protocol.
struct TrialState {
  ParallelGrasp grasp;
  Phase phase = Phase::kClosing;
  std::array<bool, 2> moving{};
  std::array<double, 2> speed{};       // m/s, each jaw's current closing speed
  std::array<double, 2> travel{};      // m, each jaw since the start
  std::array<double, 2> max_travel{};  // m, each jaw's travel down to final_opening
  std::array<double, 2> closing_force{};
  int settle_steps = 0;
  int slow_steps = 0;
  int gravity_phase = 0;
  int phase_step = 0;
  Eigen::Vector3d settled_center = Eigen::Vector3d::Zero();
  bool metrics_done = false;
  FrameRecorder recorder;
  TrialOutcome outcome;

  TrialState(const ParallelGrasp& g, const TrialParameters& p, int steps_per_phase)
      : grasp(g), recorder(p.closing_frames, p.validation_frames, steps_per_phase) {}
};

// Sum of the normal contact forces between two bodies in the environment's last step (N).
double pair_normal_force(const solver::Environment& environment, int a, int b) {
  const int lo = std::min(a, b), hi = std::max(a, b);
  for (const solver::PairForce& pair : environment.last_step().contact_forces) {
    if (pair.body_a == lo && pair.body_b == hi) return pair.normal_force;
  }
  return 0.0;
}

bool object_touches_gripper(const TrialScene& scene, const solver::Environment& environment) {
  for (const solver::PairForce& pair : environment.last_step().contact_forces) {
    const bool has_object =
        pair.body_a == scene.object_body() || pair.body_b == scene.object_body();
    if (has_object && pair.body_a != pair.body_b && pair.normal_force > 0.0) return true;
  }
  return false;
}

io::FailureKind solver_failure_kind(const std::string& reason) {
  if (reason.find("intersecting start") != std::string::npos) {
    return io::FailureKind::kInitialPenetration;
  }
  if (reason.find("Newton did not converge") != std::string::npos) {
    return io::FailureKind::kNewtonLimit;
  }
  return io::FailureKind::kNumerical;
}

std::vector<float> as_floats(const geometry::Vertices& v) {
  std::vector<float> values(static_cast<std::size_t>(v.size()));
  for (Eigen::Index r = 0; r < v.rows(); ++r) {
    for (int c = 0; c < 3; ++c) values[static_cast<std::size_t>(3 * r + c)] = static_cast<float>(v(r, c));
  }
  return values;
}

class TrialRunner {
 public:
  TrialRunner(const TrialScene& scene, const TrialRunOptions& options)
      : scene_(scene), p_(scene.parameters()), options_(options), batch_(options.threads) {
    steps_per_phase_ = std::max(1, static_cast<int>(std::lround(p_.phase_duration / p_.sim.dt)));
  }

  std::vector<TrialOutcome> run(const std::vector<ParallelGrasp>& grasps) {
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < grasps.size(); ++i) add(i, grasps[i]);
    while (batch_.any_active()) {
      batch_.step();
      for (int i = 0; i < batch_.size(); ++i) {
        if (states_[i].phase != Phase::kDone) advance(i);
      }
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::vector<TrialOutcome> outcomes;
    for (TrialState& state : states_) {
      state.outcome.result.record.wall_time = seconds / static_cast<double>(states_.size());
      outcomes.push_back(std::move(state.outcome));
    }
    return outcomes;
  }

 private:
  void add(std::size_t index, const ParallelGrasp& grasp) {
    const int i = batch_.add(scene_.model());
    solver::Environment& env = batch_.environment(i);
    try {
      scene_.place(env, grasp);
    } catch (const std::out_of_range& e) {
      throw std::out_of_range("candidate " + std::to_string(index) + ": " + e.what());
    }
    states_.emplace_back(grasp, p_, steps_per_phase_);
    TrialState& state = states_.back();
    io::CandidateRecord& record = state.outcome.result.record;
    record.id = options_.ids.empty() ? index : options_.ids.at(index);
    record.hand_poses.resize(12);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) {
        record.hand_poses[static_cast<std::size_t>(4 * r + c)] = grasp.pose.matrix()(r, c);
      }
    }
    record.joints = {grasp.opening};
    record.displacement.fill(std::numeric_limits<double>::quiet_NaN());
    for (int j = 0; j < 2; ++j) {
      state.max_travel[j] = 0.5 * (grasp.opening - p_.final_opening);
      state.moving[j] = state.max_travel[j] >= p_.closing_speed * p_.sim.dt;
      if (state.moving[j]) move_jaw(env, state, j, p_.closing_speed);
    }
    state.recorder.add_closing(frame(i));
    // The solver refuses a start whose contact pairs within d_hat touch, but a finger that
    // pierces the object with every vertex far from its surface, or lies wholly inside it, forms
    // no such pair. So the start is checked here: exact edge-triangle intersections (CGAL) and
    // gripper surface points inside the object (D1 > 0).
    if (scene::count_intersections(env) > 0 || scene_.grasp_distances(env).d1 > 0.0) {
      state.outcome.failure_reason = "the gripper intersects the object at the candidate's pose";
      record.d1 = record.d2 = std::numeric_limits<double>::quiet_NaN();
      finish(i, io::FailureKind::kInitialPenetration);
    }
  }

  void move_jaw(solver::Environment& env, TrialState& state, int j, double speed) const {
    state.speed[j] = speed;
    solver::Script script;
    script.velocity = scene_.closing_velocity(state.grasp, kJaws[j], speed);
    env.set_script(scene_.jaws()[j].jaw, script);
  }

  RecordedFrame frame(int i) const {
    const solver::Environment& env = batch_.environment(i);
    const TrialState& state = states_[i];
    RecordedFrame f;
    f.object_vertices = as_floats(env.body_vertices(scene_.object_body()));
    // Contact forces live on collision (surface) vertices; interior vertices carry none.
    f.contact_forces.assign(f.object_vertices.size(), 0.f);
    f.friction_forces.assign(f.object_vertices.size(), 0.f);
    const solver::VertexContactForces forces = env.vertex_contact_forces();
    const solver::CollisionMesh& mesh = env.model().collision();
    for (int c = 0; c < mesh.size(); ++c) {
      if (mesh.vertex_body[c] != scene_.object_body()) continue;
      for (int k = 0; k < 3; ++k) {
        f.contact_forces[3 * mesh.vertex_local[c] + k] = static_cast<float>(forces.normal(c, k));
        f.friction_forces[3 * mesh.vertex_local[c] + k] = static_cast<float>(forces.friction(c, k));
      }
    }
    f.gripper_vertices = as_floats(scene_.gripper_surface_vertices(env));
    f.object_pose = scene_.object_pose(env);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) f.hand_pose[4 * r + c] = state.grasp.pose.matrix()(r, c);
    }
    f.opening = state.grasp.opening - state.travel[0] - state.travel[1];
    if (options_.body_frames) {
      f.bodies.time = env.time();
      const int bodies = static_cast<int>(env.model().bodies().size());
      for (int b = 0; b < bodies; ++b) {
        f.bodies.vertices.push_back(env.body_vertices(b));
        f.bodies.stress.push_back(scene_.body_stress(env, b));
      }
    }
    return f;
  }

  // D1/D2 and the soft object's stress, once, at the settled grasp.
  void measure(int i) {
    TrialState& state = states_[i];
    if (state.metrics_done) return;
    state.metrics_done = true;
    const solver::Environment& env = batch_.environment(i);
    const metrics::DistanceMetrics d = scene_.grasp_distances(env);
    state.outcome.result.record.d1 = d.d1;
    state.outcome.result.record.d2 = d.d2;
    if (scene_.soft_object()) {
      const Eigen::VectorXd stress = scene_.body_stress(env, scene_.object_body());
      state.outcome.result.stress = std::vector<float>(stress.data(), stress.data() + stress.size());
    }
  }

  void advance(int i) {
    solver::Environment& env = batch_.environment(i);
    TrialState& state = states_[i];
    if (env.failed()) return fail(i);
    switch (state.phase) {
      case Phase::kClosing: close(i); break;
      case Phase::kSettling: settle(i); break;
      case Phase::kGravity: shake(i); break;
      case Phase::kDone: break;
    }
  }

  void close(int i) {
    solver::Environment& env = batch_.environment(i);
    TrialState& state = states_[i];
    for (int j = 0; j < 2; ++j) {
      if (!state.moving[j]) continue;
      state.travel[j] += state.speed[j] * p_.sim.dt;
      const double force = pair_normal_force(env, scene_.object_body(), scene_.jaws()[j].finger);
      const double speed = force > 0.0 ? p_.squeeze_speed : state.speed[j];
      if (force > p_.stop_force || state.travel[j] + speed * p_.sim.dt > state.max_travel[j]) {
        state.moving[j] = false;
        state.closing_force[j] = force;
        env.set_script(scene_.jaws()[j].jaw, solver::Script{});
      } else if (speed != state.speed[j]) {
        move_jaw(env, state, j, speed);
      }
    }
    if (state.recorder.closing_step()) state.recorder.add_closing(frame(i));
    if (!state.moving[0] && !state.moving[1]) state.phase = Phase::kSettling;
  }

  void settle(int i) {
    solver::Environment& env = batch_.environment(i);
    TrialState& state = states_[i];
    ++state.settle_steps;
    const double speed = env.center_of_mass_velocity(scene_.object_body()).norm();
    state.slow_steps = speed < p_.settle_speed ? state.slow_steps + 1 : 0;
    const bool settled = state.slow_steps >= p_.settle_steps ||
                         state.settle_steps >= p_.settle_max_steps;
    if (!settled) {
      if (state.recorder.closing_step()) state.recorder.add_closing(frame(i));
      return;
    }
    state.recorder.closing_step();
    state.recorder.add_settled(frame(i));
    measure(i);
    io::CandidateRecord& record = state.outcome.result.record;
    record.closing_forces = {state.closing_force[0], state.closing_force[1]};
    if (!object_touches_gripper(scene_, env)) {
      return finish(i, io::FailureKind::kNoContact);
    }
    state.settled_center = env.center_of_mass(scene_.object_body());
    state.phase = Phase::kGravity;
    env.set_gravity(p_.gravity_magnitude * kGravityAxes[0]);
  }

  void shake(int i) {
    solver::Environment& env = batch_.environment(i);
    TrialState& state = states_[i];
    ++state.phase_step;
    if (state.recorder.validation_due(state.phase_step)) state.recorder.add_validation(frame(i));
    if (state.phase_step < steps_per_phase_) return;
    io::CandidateRecord& record = state.outcome.result.record;
    record.displacement[state.gravity_phase] =
        (env.center_of_mass(scene_.object_body()) - state.settled_center).norm();
    state.phase_step = 0;
    if (++state.gravity_phase < 6) {
      env.set_gravity(p_.gravity_magnitude * kGravityAxes[state.gravity_phase]);
      return;
    }
    if (!object_touches_gripper(scene_, env)) return finish(i, io::FailureKind::kLostContact);
    double largest = 0.0;
    for (double d : record.displacement) largest = std::max(largest, d);
    finish(i, largest < p_.displacement_threshold() ? io::FailureKind::kNone
                                                    : io::FailureKind::kDisplaced);
  }

  // A failed environment's state is not a grasp (a step may have stopped half-way): its
  // frames end at the last accepted step, and D1/D2 are not measured (NaN).
  void fail(int i) {
    TrialState& state = states_[i];
    const solver::Environment& env = batch_.environment(i);
    state.outcome.failure_reason = env.failure();
    io::CandidateRecord& record = state.outcome.result.record;
    if (state.phase != Phase::kGravity) {
      record.closing_forces = {state.closing_force[0], state.closing_force[1]};
    }
    if (!state.metrics_done) {
      record.d1 = record.d2 = std::numeric_limits<double>::quiet_NaN();
    }
    finish(i, solver_failure_kind(env.failure()));
  }

  void finish(int i, io::FailureKind failure) {
    TrialState& state = states_[i];
    const solver::Environment& env = batch_.environment(i);
    io::CandidateRecord& record = state.outcome.result.record;
    record.status = failure == io::FailureKind::kNone ? io::Status::kSuccess : io::Status::kFailure;
    record.failure = failure;
    const solver::EnvironmentStatistics& stats = env.statistics();
    record.newton.steps = static_cast<std::uint32_t>(stats.steps);
    record.newton.iterations = static_cast<std::uint32_t>(stats.newton_iterations);
    record.newton.max_iterations = static_cast<std::uint32_t>(stats.max_step_iterations);
    std::vector<RecordedFrame> frames = state.recorder.frames();
    if (options_.trajectory) state.outcome.result.trajectory = trajectory_record(frames);
    if (options_.body_frames) {
      for (RecordedFrame& f : frames) state.outcome.body_frames.push_back(std::move(f.bodies));
    }
    state.recorder = FrameRecorder(p_.closing_frames, p_.validation_frames, steps_per_phase_);
    state.phase = Phase::kDone;
    batch_.retire(i);
  }

  const TrialScene& scene_;
  const TrialParameters& p_;
  const TrialRunOptions& options_;
  solver::Batch batch_;
  int steps_per_phase_ = 1;
  std::vector<TrialState> states_;
};

}  // namespace

std::vector<TrialOutcome> run_trials(const TrialScene& scene,
                                     const std::vector<ParallelGrasp>& grasps,
                                     const TrialRunOptions& options) {
  if (!options.ids.empty() && options.ids.size() != grasps.size()) {
    throw std::invalid_argument("run_trials: " + std::to_string(options.ids.size()) + " ids for " +
                                std::to_string(grasps.size()) + " candidates");
  }
  TrialRunner runner(scene, options);
  return runner.run(grasps);
}

}  // namespace grip::trial
