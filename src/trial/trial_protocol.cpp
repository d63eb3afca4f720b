#include "src/trial/trial_protocol.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "solver/batch/batch.hpp"
#include "src/scene/invariants.hpp"
#include "src/trial/frame_recorder.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace grip::trial {

namespace {

// Gravity directions of the six validation phases, in order.
const std::array<Eigen::Vector3d, 6> kGravityAxes = {
    Eigen::Vector3d::UnitX(),  -Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
    -Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),  -Eigen::Vector3d::UnitZ()};

enum class Phase { kClosing, kSettling, kGravity, kDone };

// One candidate's progress through the protocol.
struct TrialState {
  std::size_t candidate = 0;
  Phase phase = Phase::kClosing;
  std::vector<char> moving;        // per finger
  std::vector<double> speed;       // m/s, each finger's current closing speed
  std::vector<double> travel;      // m, each finger since the start
  std::vector<double> max_travel;  // m, each finger's longest travel
  std::vector<double> closing_force;
  int settle_steps = 0;
  int slow_steps = 0;
  int gravity_phase = 0;
  int phase_step = 0;
  Eigen::Vector3d settled_center = Eigen::Vector3d::Zero();
  bool metrics_done = false;
  FrameRecorder recorder;
  TrialOutcome outcome;

  TrialState(std::size_t k, int fingers, const TrialParameters& p, int steps_per_phase)
      : candidate(k),
        moving(fingers, 0),
        speed(fingers, 0.0),
        travel(fingers, 0.0),
        max_travel(fingers, 0.0),
        closing_force(fingers, 0.0),
        recorder(p.closing_frames, p.validation_frames, steps_per_phase) {}
};

// Sum of the normal contact forces between two bodies in the environment's last step (N).
double pair_normal_force(const solver::Environment& environment, int a, int b) {
  const int lo = std::min(a, b), hi = std::max(a, b);
  for (const solver::PairForce& pair : environment.last_step().contact_forces) {
    if (pair.body_a == lo && pair.body_b == hi) return pair.normal_force;
  }
  return 0.0;
}

bool object_touches_gripper(int object, const solver::Environment& environment) {
  for (const solver::PairForce& pair : environment.last_step().contact_forces) {
    const bool has_object = pair.body_a == object || pair.body_b == object;
    if (has_object && pair.body_a != pair.body_b && pair.normal_force > 0.0) return true;
  }
  return false;
}

// The one map from the solver's failure codes to the dataset's failure kinds.
io::FailureKind solver_failure_kind(solver::Failure failure) {
  switch (failure) {
    case solver::Failure::kIntersectingStart:
      return io::FailureKind::kInitialPenetration;
    case solver::Failure::kNewtonLimit:
      return io::FailureKind::kNewtonLimit;
    case solver::Failure::kNone:
    case solver::Failure::kNonFinite:
    case solver::Failure::kLinearSolve:
    case solver::Failure::kCcdNoMotion:
    case solver::Failure::kInversion:
    case solver::Failure::kLineSearch:
      break;
  }
  return io::FailureKind::kNumerical;
}

std::vector<float> as_floats(const geometry::Vertices& v) {
  std::vector<float> values(static_cast<std::size_t>(v.size()));
  for (Eigen::Index r = 0; r < v.rows(); ++r) {
    for (int c = 0; c < 3; ++c) {
      values[static_cast<std::size_t>(3 * r + c)] = static_cast<float>(v(r, c));
    }
  }
  return values;
}

class ProtocolRunner {
 public:
  ProtocolRunner(const TrialGripper& gripper, const TrialRunOptions& options)
      : gripper_(gripper),
        p_(gripper.parameters()),
        options_(options),
        fingers_(gripper.finger_count()),
        batch_(options.threads),
        arena_(batch_.threads()) {
    steps_per_phase_ = std::max(1, static_cast<int>(std::lround(p_.phase_duration / p_.sim.dt)));
  }

  std::vector<TrialOutcome> run() {
    const auto start = std::chrono::steady_clock::now();
    // The protocol's work between steps (start checks, contact forces, D1/D2 at 50,000 points,
    // frames) touches only its own environment and state: it runs on the batch's threads too.
    start_more();
    while (batch_.any_active() || next_ < gripper_.candidate_count()) {
      batch_.step();
      for_each_environment(0, [&](int i) {
        if (states_[i].phase != Phase::kDone) advance(i);
      });
      start_more();
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
  void add(std::size_t k) {
    const int i = batch_.add(gripper_.model());
    solver::Environment& env = batch_.environment(i);
    std::vector<double> max_travel;
    try {
      max_travel = gripper_.place(env, k);
    } catch (const std::out_of_range& e) {
      throw std::out_of_range("candidate " + std::to_string(k) + ": " + e.what());
    }
    states_.emplace_back(k, fingers_, p_, steps_per_phase_);
    TrialState& state = states_.back();
    io::CandidateRecord& record = state.outcome.result.record;
    record.id = options_.ids.empty() ? k : options_.ids.at(k);
    record.hand_poses.resize(12);
    const Eigen::Isometry3d& pose = gripper_.pose(k);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) {
        record.hand_poses[static_cast<std::size_t>(4 * r + c)] = pose.matrix()(r, c);
      }
    }
    record.joints = gripper_.joints(k, state.travel);
    record.displacement.fill(std::numeric_limits<double>::quiet_NaN());
    for (int j = 0; j < fingers_; ++j) {
      state.max_travel[j] = max_travel.at(static_cast<std::size_t>(j));
      state.moving[j] = state.max_travel[j] >= p_.closing_speed * p_.sim.dt;
      if (state.moving[j]) {
        state.speed[j] = p_.closing_speed;
        gripper_.move_finger(env, k, j, 0.0, p_.closing_speed);
      }
    }
    state.recorder.add_closing(frame(i));
  }

  // Adds candidates until max_active trials run (environments are added in candidate order,
  // so environment i is candidate i) and checks their starts.
  void start_more() {
    const std::size_t limit = options_.max_active > 0
                                  ? static_cast<std::size_t>(options_.max_active)
                                  : gripper_.candidate_count();
    std::size_t running = 0;
    for (const TrialState& state : states_) running += state.phase != Phase::kDone;
    const int first = batch_.size();
    for (; running < limit && next_ < gripper_.candidate_count(); ++running) add(next_++);
    for_each_environment(first, [&](int i) { check_start(i); });
  }

  template <typename Work>
  void for_each_environment(int first, Work&& work) {
    if (first >= batch_.size()) return;
    arena_.execute([&] { tbb::parallel_for(first, batch_.size(), [&](int i) { work(i); }); });
  }

  void check_start(int i) {
    TrialState& state = states_[i];
    io::CandidateRecord& record = state.outcome.result.record;
    const solver::Environment& env = batch_.environment(i);
    // The solver refuses a start whose contact pairs within d_hat touch, but a finger that
    // pierces the object with every vertex far from its surface, or lies wholly inside it, forms
    // no such pair. So the start is checked here: exact edge-triangle intersections (CGAL) and
    // gripper surface points inside the object (D1 > 0).
    if (scene::count_intersections(env) > 0 || gripper_.grasp_distances(env).d1 > 0.0) {
      state.outcome.failure_reason = "the gripper intersects the object at the candidate's pose";
      record.d1 = record.d2 = std::numeric_limits<double>::quiet_NaN();
      finish(i, io::FailureKind::kInitialPenetration);
    }
  }

  double finger_force(const solver::Environment& env, int finger) const {
    double force = 0.0;
    for (int body : gripper_.finger_bodies(finger)) {
      force += pair_normal_force(env, gripper_.object_body(), body);
    }
    return force;
  }

  RecordedFrame frame(int i) {
    const solver::Environment& env = batch_.environment(i);
    TrialState& state = states_[i];
    const int object = gripper_.object_body();
    RecordedFrame f;
    f.object_vertices = as_floats(env.body_vertices(object));
    // Contact forces live on collision (surface) vertices; interior vertices carry none.
    f.contact_forces.assign(f.object_vertices.size(), 0.f);
    f.friction_forces.assign(f.object_vertices.size(), 0.f);
    const solver::VertexContactForces forces = env.vertex_contact_forces();
    const solver::CollisionMesh& mesh = env.model().collision();
    for (int c = 0; c < mesh.size(); ++c) {
      if (mesh.vertex_body[c] != object) continue;
      for (int k = 0; k < 3; ++k) {
        f.contact_forces[3 * mesh.vertex_local[c] + k] = static_cast<float>(forces.normal(c, k));
        f.friction_forces[3 * mesh.vertex_local[c] + k] = static_cast<float>(forces.friction(c, k));
      }
    }
    f.gripper_vertices = as_floats(gripper_.surface_vertices(env));
    f.object_pose = gripper_.object_pose(env);
    const Eigen::Isometry3d& pose = gripper_.pose(state.candidate);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) f.hand_pose[4 * r + c] = pose.matrix()(r, c);
    }
    f.joints = gripper_.joints(state.candidate, state.travel);
    if (options_.body_frames) {
      f.bodies.time = env.time();
      const int bodies = static_cast<int>(env.model().bodies().size());
      for (int b = 0; b < bodies; ++b) {
        f.bodies.vertices.push_back(env.body_vertices(b));
        f.bodies.stress.push_back(gripper_.body_stress(env, b));
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
    const metrics::DistanceMetrics d = gripper_.grasp_distances(env);
    state.outcome.result.record.d1 = d.d1;
    state.outcome.result.record.d2 = d.d2;
    if (gripper_.soft_object()) {
      const Eigen::VectorXd stress = gripper_.body_stress(env, gripper_.object_body());
      state.outcome.result.stress =
          std::vector<float>(stress.data(), stress.data() + stress.size());
    }
  }

  void advance(int i) {
    solver::Environment& env = batch_.environment(i);
    TrialState& state = states_[i];
    if (env.failed()) return fail(i);
    switch (state.phase) {
      case Phase::kClosing:
        close(i);
        break;
      case Phase::kSettling:
        settle(i);
        break;
      case Phase::kGravity:
        shake(i);
        break;
      case Phase::kDone:
        break;
    }
  }

  void close(int i) {
    solver::Environment& env = batch_.environment(i);
    TrialState& state = states_[i];
    bool any_moving = false;
    for (int j = 0; j < fingers_; ++j) {
      if (!state.moving[j]) continue;
      state.travel[j] += state.speed[j] * p_.sim.dt;
      const double force = finger_force(env, j);
      const double speed = force > 0.0 ? p_.squeeze_speed : state.speed[j];
      if (force > p_.stop_force || state.travel[j] + speed * p_.sim.dt > state.max_travel[j]) {
        state.moving[j] = 0;
        state.closing_force[j] = force;
        gripper_.hold_finger(env, j);
      } else {
        state.speed[j] = speed;
        gripper_.move_finger(env, state.candidate, j, state.travel[j], speed);
        any_moving = true;
      }
    }
    if (state.recorder.closing_step()) state.recorder.add_closing(frame(i));
    if (!any_moving) state.phase = Phase::kSettling;
  }

  void settle(int i) {
    solver::Environment& env = batch_.environment(i);
    TrialState& state = states_[i];
    ++state.settle_steps;
    const double speed = env.center_of_mass_velocity(gripper_.object_body()).norm();
    state.slow_steps = speed < p_.settle_speed ? state.slow_steps + 1 : 0;
    const bool settled =
        state.slow_steps >= p_.settle_steps || state.settle_steps >= p_.settle_max_steps;
    if (!settled) {
      if (state.recorder.closing_step()) state.recorder.add_closing(frame(i));
      return;
    }
    state.recorder.closing_step();
    state.recorder.add_settled(frame(i));
    measure(i);
    io::CandidateRecord& record = state.outcome.result.record;
    record.closing_forces = state.closing_force;
    if (!object_touches_gripper(gripper_.object_body(), env)) {
      return finish(i, io::FailureKind::kNoContact);
    }
    state.settled_center = env.center_of_mass(gripper_.object_body());
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
        (env.center_of_mass(gripper_.object_body()) - state.settled_center).norm();
    state.phase_step = 0;
    if (++state.gravity_phase < 6) {
      env.set_gravity(p_.gravity_magnitude * kGravityAxes[state.gravity_phase]);
      return;
    }
    if (!object_touches_gripper(gripper_.object_body(), env)) {
      return finish(i, io::FailureKind::kLostContact);
    }
    double largest = 0.0;
    for (double d : record.displacement) largest = std::max(largest, d);
    finish(i, largest < p_.displacement_threshold() ? io::FailureKind::kNone
                                                    : io::FailureKind::kDisplaced);
  }

  // A failed environment's state is not a grasp (a step may have stopped half-way): its
  // frames end at the last accepted step, and D1/D2 are not measured (NaN). A solver failure
  // after a gravity phase already moved the object beyond the threshold does not decide the
  // verdict: the grasp had failed (`displaced`) before; failure_reason keeps the solver's word.
  void fail(int i) {
    TrialState& state = states_[i];
    const solver::Environment& env = batch_.environment(i);
    state.outcome.failure_reason = env.failure();
    io::CandidateRecord& record = state.outcome.result.record;
    if (state.phase != Phase::kGravity) record.closing_forces = state.closing_force;
    if (!state.metrics_done) {
      record.d1 = record.d2 = std::numeric_limits<double>::quiet_NaN();
    }
    const bool displaced_before =
        state.phase == Phase::kGravity &&
        std::any_of(record.displacement.begin(), record.displacement.begin() + state.gravity_phase,
                    [&](double d) { return d >= p_.displacement_threshold(); });
    finish(i, displaced_before ? io::FailureKind::kDisplaced
                               : solver_failure_kind(env.failure_code()));
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
    record.newton.retries = static_cast<std::uint32_t>(stats.retries);
    state.outcome.steps_by_newton_iterations = stats.steps_by_iterations;
    std::vector<RecordedFrame> frames = state.recorder.frames();
    if (options_.trajectory) state.outcome.result.trajectory = trajectory_record(frames);
    if (options_.body_frames) {
      for (RecordedFrame& f : frames) state.outcome.body_frames.push_back(std::move(f.bodies));
    }
    state.recorder = FrameRecorder(p_.closing_frames, p_.validation_frames, steps_per_phase_);
    state.phase = Phase::kDone;
    batch_.retire(i);
  }

  const TrialGripper& gripper_;
  const TrialParameters& p_;
  const TrialRunOptions& options_;
  int fingers_ = 0;
  solver::Batch batch_;
  tbb::task_arena arena_;
  int steps_per_phase_ = 1;
  std::vector<TrialState> states_;
  std::size_t next_ = 0;  // the next candidate to start
};

}  // namespace

std::vector<TrialOutcome> run_protocol(const TrialGripper& gripper,
                                       const TrialRunOptions& options) {
  if (!options.ids.empty() && options.ids.size() != gripper.candidate_count()) {
    throw std::invalid_argument("run_trials: " + std::to_string(options.ids.size()) + " ids for " +
                                std::to_string(gripper.candidate_count()) + " candidates");
  }
  ProtocolRunner runner(gripper, options);
  return runner.run();
}

}  // namespace grip::trial
