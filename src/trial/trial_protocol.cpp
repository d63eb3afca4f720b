#include "src/trial/trial_protocol.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "solver/batch/engines.hpp"
#include "src/scene/invariants.hpp"
#include "src/trial/contact_patch.hpp"
#include "src/trial/finger_servo.hpp"
#include "src/trial/frame_recorder.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace grip::trial {

namespace {

enum class Phase { kClosing, kSettling, kGravity, kDone };

// Placement's broad-phase reach (m), its most moves per finger, and how close to the gap a
// finger counts as placed (a fraction of the gap).
constexpr double kPlacementSearch = 0.02;
constexpr int kPlacementMoves = 32;
constexpr double kPlacementTolerance = 0.1;

// A gravity phase stops waiting for the object to come to rest once it has slipped this many
// verdict thresholds (TrialParameters::rest_duration).
constexpr double kSlidThreshold = 10.0;

// One candidate's progress through the protocol.
struct TrialState {
  std::size_t candidate = 0;
  Phase phase = Phase::kClosing;
  std::vector<FingerServo> fingers;
  int steady_steps = 0;                                           // in a row
  int squeeze_steps = 0;                                          // closing and settling
  Eigen::Matrix3d object_rotation = Eigen::Matrix3d::Identity();  // at the last step
  int gravity_phase = 0;
  int phase_step = 0;
  // The object's speed over the phase's last steps, as a ring (TrialOutcome::end_speed); zero
  // where a phase has not yet taken that many steps.
  std::array<double, TrialOutcome::kEndSpeedSteps> recent_speed{};
  Eigen::Vector3d start_center = Eigen::Vector3d::Zero();  // the object's, at the candidate's start
  Eigen::Vector3d settled_center = Eigen::Vector3d::Zero();
  // The settled grasp's contact patches, the gripper's and (a soft object's) the object's,
  // against which slip is measured.
  ContactPatch gripper_patch;
  ContactPatch object_patch;
  bool metrics_done = false;
  // The verdict, once a gravity phase's end has decided it (decide_at_phase_end).
  std::optional<io::FailureKind> decided;
  FrameRecorder recorder;
  TrialOutcome outcome;

  TrialState(std::size_t k, const TrialParameters& p, int steps_per_phase)
      : candidate(k), recorder(p.closing_frames, p.validation_frames, steps_per_phase) {}

  std::vector<double> travel() const {
    std::vector<double> t;
    for (const FingerServo& f : fingers) t.push_back(f.travel());
    return t;
  }
};

// Sum of the normal contact forces between two bodies in the environment's last step (N).
double pair_normal_force(const solver::EnvironmentHandle& environment, int a, int b) {
  const int lo = std::min(a, b), hi = std::max(a, b);
  for (const solver::PairForce& pair : environment.last_step().contact_forces) {
    if (pair.body_a == lo && pair.body_b == hi) return pair.normal_force;
  }
  return 0.0;
}

bool object_touches_gripper(int object, const solver::EnvironmentHandle& environment) {
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

// The dataset's layout of the grippers' poses: row-major 3x4 [R | t] per gripper.
std::vector<double> pose_values(const std::vector<Eigen::Isometry3d>& poses) {
  std::vector<double> values;
  for (const Eigen::Isometry3d& pose : poses) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) values.push_back(pose.matrix()(r, c));
    }
  }
  return values;
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

// The collision vertex of each of `vertices`, or -1 where the vertex is not one.
std::vector<int> collision_vertices(const solver::CollisionMesh& mesh,
                                    const std::vector<BodyVertex>& vertices) {
  std::vector<int> collision;
  collision.reserve(vertices.size());
  for (const BodyVertex& v : vertices) {
    int found = -1;
    const auto b = static_cast<std::size_t>(v.body);
    for (int c = mesh.body_first_vertex[b]; c < mesh.body_first_vertex[b + 1]; ++c) {
      if (mesh.vertex_local[c] == v.vertex) {
        found = c;
        break;
      }
    }
    collision.push_back(found);
  }
  return collision;
}

class ProtocolRunner {
 public:
  ProtocolRunner(const TrialGripper& gripper, const TrialRunOptions& options)
      : gripper_(gripper),
        p_(gripper.parameters()),
        options_(options),
        fingers_(gripper.finger_count()),
        engine_(solver::make_engine(options.device, options.threads)),
        arena_(engine_->threads()) {
    steps_per_phase_ = static_cast<int>(phase_steps(p_));
    max_steps_per_phase_ = steps_per_phase_ + static_cast<int>(rest_steps(p_));
    gripper_collision_ =
        collision_vertices(gripper_.model()->collision(), gripper_.surface_sources());
  }

  std::vector<TrialOutcome> run() {
    const auto start = std::chrono::steady_clock::now();
    // The protocol's work between steps (start checks, contact forces, D1/D2 at 50,000 points,
    // frames) touches only its own environment and state: it runs on the batch's threads too.
    start_more();
    while (engine_->any_active() || next_ < gripper_.candidate_count()) {
      engine_->step();
      for_each_environment(0, [&](int i) {
        if (states_[i].phase != Phase::kDone) advance(i);
      });
      start_more();
      if (options_.after_step) options_.after_step(ended());
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
  std::size_t ended() const {
    return static_cast<std::size_t>(
        std::count_if(states_.begin(), states_.end(),
                      [](const TrialState& s) { return s.phase == Phase::kDone; }));
  }

  void add(std::size_t k) {
    const int i = engine_->add(gripper_.model());
    solver::EnvironmentHandle& env = engine_->environment(i);
    if (options_.big_system_solver) env.use_linear_solver(options_.big_system_solver, 0);
    std::vector<double> max_travel;
    try {
      max_travel = gripper_.place(env, k);
    } catch (const std::out_of_range& e) {
      throw std::out_of_range("candidate " + std::to_string(k) + ": " + e.what());
    }
    states_.emplace_back(k, p_, steps_per_phase_);
    TrialState& state = states_.back();
    io::CandidateRecord& record = state.outcome.result.record;
    record.id = options_.ids.empty() ? k : options_.ids.at(k);
    record.hand_poses = pose_values(gripper_.poses(k));
    record.joints = gripper_.joints(k, std::vector<double>(fingers_, 0.0));
    record.contact_friction =
        gripper_.model()->pair_friction(gripper_.object_body(), gripper_.finger_bodies(0).front());
    record.displacement.fill(std::numeric_limits<double>::quiet_NaN());
    record.phase_seconds.fill(std::numeric_limits<double>::quiet_NaN());
    for (int j = 0; j < fingers_; ++j) {
      const double longest = max_travel.at(static_cast<std::size_t>(j));
      state.fingers.emplace_back(place_near_object(env, k, j, longest), longest, p_.grip_force,
                                 p_.force_tolerance * p_.grip_force);
    }
    const int object = gripper_.object_body();
    state.object_rotation = env.rotation(object);
    state.start_center = env.center_of_mass(object);
    // Held where the candidate found it while the fingers close, as a table would hold it: a
    // free, weightless object would be pushed away by the first finger to touch it.
    env.hold(object);
    state.recorder.add_closing(frame(i));
    command(i);
  }

  // Places finger j along its closing path placement_gap * d_hat from the object (an exact
  // distance query), or at the end of its path if nothing lies on it, so that no step closes on
  // air and nothing arrives with momentum; returns its travel. Conservative advancement: each
  // move is at most the free distance, measured as the largest displacement of any vertex of
  // the finger (a hand's finger turns, so travel and displacement differ).
  double place_near_object(solver::EnvironmentHandle& env, std::size_t k, int j,
                           double max_travel) {
    const double gap = p_.placement_gap * p_.sim.d_hat;
    const double search = std::max(10.0 * gap, kPlacementSearch);
    const std::vector<int>& bodies = gripper_.finger_bodies(j);
    const auto finger_vertices = [&] {
      std::vector<geometry::Vertices> v;
      for (int b : bodies) v.push_back(env.body_vertices(b));
      return v;
    };
    double travel = 0.0;
    std::vector<geometry::Vertices> at = finger_vertices();
    for (int move = 0; move < kPlacementMoves && travel < max_travel; ++move) {
      const double free =
          std::min(env.surface_distance(bodies, gripper_.object_body(), search), search) - gap;
      if (free <= kPlacementTolerance * gap) break;
      double step = std::min(free, max_travel - travel);
      for (int shrink = 0; shrink < kPlacementMoves; ++shrink) {
        gripper_.place_finger(env, k, j, travel, travel + step);
        const std::vector<geometry::Vertices> next = finger_vertices();
        double moved = 0.0;
        for (std::size_t b = 0; b < next.size(); ++b) {
          moved = std::max(moved, (next[b] - at[b]).rowwise().norm().maxCoeff());
        }
        if (moved <= free) {
          at = next;
          travel += step;
          break;
        }
        gripper_.place_finger(env, k, j, travel + step, travel);
        step *= 0.9 * free / moved;
      }
    }
    return travel;
  }

  // Adds candidates until max_active trials run (environments are added in candidate order,
  // so environment i is candidate i) and checks their starts.
  void start_more() {
    const std::size_t limit = options_.max_active > 0
                                  ? static_cast<std::size_t>(options_.max_active)
                                  : gripper_.candidate_count();
    std::size_t running = 0;
    for (const TrialState& state : states_) running += state.phase != Phase::kDone;
    const int first = engine_->size();
    for (; running < limit && next_ < gripper_.candidate_count(); ++running) add(next_++);
    for_each_environment(first, [&](int i) { check_start(i); });
  }

  template <typename Work>
  void for_each_environment(int first, Work&& work) {
    if (first >= engine_->size()) return;
    arena_.execute([&] { tbb::parallel_for(first, engine_->size(), [&](int i) { work(i); }); });
  }

  void check_start(int i) {
    TrialState& state = states_[i];
    io::CandidateRecord& record = state.outcome.result.record;
    const solver::EnvironmentHandle& env = engine_->environment(i);
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

  double finger_force(const solver::EnvironmentHandle& env, int finger) const {
    double force = 0.0;
    for (int body : gripper_.finger_bodies(finger)) {
      force += pair_normal_force(env, gripper_.object_body(), body);
    }
    return force;
  }

  RecordedFrame frame(int i) {
    solver::EnvironmentHandle& env = engine_->environment(i);
    TrialState& state = states_[i];
    const int object = gripper_.object_body();
    RecordedFrame f;
    f.object_vertices = as_floats(env.body_vertices(object));
    // Contact forces live on collision (surface) vertices; interior vertices carry none.
    const solver::VertexContactForces forces = env.vertex_contact_forces();
    const auto put = [&forces](int c, std::size_t row, std::vector<float>& normal,
                               std::vector<float>& friction) {
      for (int k = 0; k < 3; ++k) {
        normal[3 * row + static_cast<std::size_t>(k)] = static_cast<float>(forces.normal(c, k));
        friction[3 * row + static_cast<std::size_t>(k)] = static_cast<float>(forces.friction(c, k));
      }
    };
    f.contact_forces.assign(f.object_vertices.size(), 0.f);
    f.friction_forces.assign(f.object_vertices.size(), 0.f);
    const solver::CollisionMesh& mesh = env.model().collision();
    for (int c = mesh.body_first_vertex[static_cast<std::size_t>(object)];
         c < mesh.body_first_vertex[static_cast<std::size_t>(object) + 1]; ++c) {
      put(c, static_cast<std::size_t>(mesh.vertex_local[c]), f.contact_forces, f.friction_forces);
    }
    f.gripper_vertices = as_floats(gripper_.surface_vertices(env));
    f.gripper_contact_forces.assign(f.gripper_vertices.size(), 0.f);
    f.gripper_friction_forces.assign(f.gripper_vertices.size(), 0.f);
    for (std::size_t v = 0; v < gripper_collision_.size(); ++v) {
      if (gripper_collision_[v] >= 0) {
        put(gripper_collision_[v], v, f.gripper_contact_forces, f.gripper_friction_forces);
      }
    }
    f.object_pose = gripper_.object_pose(env);
    f.hand_poses = pose_values(gripper_.poses(state.candidate));
    f.joints = gripper_.joints(state.candidate, state.travel());
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

  // D1/D2 and the soft object's and soft fingers' stress, once, at the settled grasp.
  void measure(int i) {
    TrialState& state = states_[i];
    if (state.metrics_done) return;
    state.metrics_done = true;
    const solver::EnvironmentHandle& env = engine_->environment(i);
    const metrics::DistanceMetrics d = gripper_.grasp_distances(env);
    state.outcome.result.record.d1 = d.d1;
    state.outcome.result.record.d2 = d.d2;
    state.outcome.gripper_distances = gripper_.gripper_distances(env);
    if (gripper_.soft_object()) {
      const Eigen::VectorXd stress = gripper_.body_stress(env, gripper_.object_body());
      state.outcome.result.stress =
          std::vector<float>(stress.data(), stress.data() + stress.size());
    }
    const Eigen::VectorXd fingers = gripper_.finger_stress(env);
    if (fingers.size() > 0) {
      state.outcome.result.finger_stress =
          std::vector<float>(fingers.data(), fingers.data() + fingers.size());
    }
  }

  void advance(int i) {
    solver::EnvironmentHandle& env = engine_->environment(i);
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

  // Closing, on the held object: every finger approaches at squeeze_speed until it touches the
  // object or reaches the end of its path, then servos its travel so that its force settles on
  // grip_force. Once every finger is on target or at the end of its path, closing ends: the
  // object is released, and each finger from then on acts as a spring preloaded with its force
  // (the paper's "halted", with the drive's compliance: a finger held rigidly would lose its
  // whole force to a creep of a few hundredths of a millimetre, so stiff is the barrier).
  void close(int i) {
    solver::EnvironmentHandle& env = engine_->environment(i);
    TrialState& state = states_[i];
    bool closed = true;
    for (int j = 0; j < fingers_; ++j) {
      FingerServo& finger = state.fingers[j];
      finger.observe(finger_force(env, j));
      closed = closed && (finger.at_limit() || finger.on_target());
    }
    ++state.squeeze_steps;
    if (!closed) {
      if (state.squeeze_steps >= p_.settle_max_steps) return unsettled(i);
      command(i);
      if (state.recorder.closing_step()) state.recorder.add_closing(frame(i));
      return;
    }
    state.outcome.result.record.closing_forces = finger_forces(state);
    state.outcome.closed = true;
    for (FingerServo& finger : state.fingers) {
      state.outcome.closing_at_path_end.push_back(finger.at_limit());
      if (gripper_.driven_fingers()) {
        finger.halt();
      } else {
        finger.hold_as_spring(p_.finger_stiffness);
      }
    }
    env.release(gripper_.object_body());
    state.phase = Phase::kSettling;
    command(i);
    if (state.recorder.closing_step()) state.recorder.add_closing(frame(i));
  }

  // Each finger's motion over the next step: its servo's while closing, its spring's after.
  void command(int i) {
    solver::EnvironmentHandle& env = engine_->environment(i);
    TrialState& state = states_[i];
    const double max_step = p_.squeeze_speed * p_.sim.dt;
    for (int j = 0; j < fingers_; ++j) {
      FingerServo& finger = state.fingers[j];
      const double increment = finger.next_increment(max_step);
      if (increment == 0.0) {
        gripper_.hold_finger(env, j);
      } else {
        gripper_.move_finger(env, state.candidate, j, finger.travel(), increment / p_.sim.dt);
      }
      finger.advance(increment);
    }
  }

  void unsettled(int i) {
    TrialState& state = states_[i];
    state.outcome.failure_reason = "not steady after " + std::to_string(state.squeeze_steps) +
                                   " steps of closing and settling";
    io::CandidateRecord& record = state.outcome.result.record;
    if (state.phase == Phase::kClosing) record.closing_forces = finger_forces(state);
    record.d1 = record.d2 = std::numeric_limits<double>::quiet_NaN();  // no settled grasp
    // The closing frames end with the state the trial stopped in.
    state.recorder.closing_step();
    state.recorder.add_settled(frame(i));
    finish(i, io::FailureKind::kUnsettled);
  }

  // Still: the object's linear and angular speeds below settle_speed and settle_angular_speed
  // (its rotation is tracked from one step to the next).
  bool still(int i) {
    const solver::EnvironmentHandle& env = engine_->environment(i);
    TrialState& state = states_[i];
    const int object = gripper_.object_body();
    const Eigen::Matrix3d rotation = env.rotation(object);
    const double turned = Eigen::AngleAxisd(state.object_rotation.transpose() * rotation).angle();
    state.object_rotation = rotation;
    return env.center_of_mass_velocity(object).norm() < p_.settle_speed &&
           turned / p_.sim.dt < p_.settle_angular_speed;
  }

  // Steady: the object still, and no finger's force changing by more than force_tolerance *
  // grip_force over the step.
  bool steady(int i) {
    if (!still(i)) return false;
    const double tolerance = p_.force_tolerance * p_.grip_force;
    const std::vector<FingerServo>& fingers = states_[i].fingers;
    return std::all_of(fingers.begin(), fingers.end(), [&](const FingerServo& f) {
      return std::abs(f.force() - f.previous_force()) <= tolerance;
    });
  }

  // Settling, fingers on their springs and the object free (gravity still off): until the grasp is
  // steady for settle_steps steps in a row. An object that touches no finger any more was not
  // grasped.
  void settle(int i) {
    solver::EnvironmentHandle& env = engine_->environment(i);
    TrialState& state = states_[i];
    ++state.squeeze_steps;
    for (int j = 0; j < fingers_; ++j) state.fingers[j].observe(finger_force(env, j));
    if (!object_touches_gripper(gripper_.object_body(), env)) {
      measure(i);
      return finish(i, io::FailureKind::kNoContact);
    }
    command(i);
    state.steady_steps = steady(i) ? state.steady_steps + 1 : 0;
    if (state.steady_steps < p_.settle_steps) {
      if (state.squeeze_steps >= p_.settle_max_steps) return unsettled(i);
      if (state.recorder.closing_step()) state.recorder.add_closing(frame(i));
      return;
    }
    state.recorder.closing_step();
    state.recorder.add_settled(frame(i));
    measure(i);
    state.settled_center = env.center_of_mass(gripper_.object_body());
    state.outcome.settle_displacement = (state.settled_center - state.start_center).norm();
    record_patch(i);
    state.phase = Phase::kGravity;
    state.steady_steps = 0;
    env.set_gravity(p_.gravity_magnitude * kGravityAxes[0]);
  }

  // The settled grasp's contact patches: the collision vertices that bear a contact force,
  // weighted by its magnitude.
  void record_patch(int i) {
    solver::EnvironmentHandle& env = engine_->environment(i);
    TrialState& state = states_[i];
    const solver::VertexContactForces forces = env.vertex_contact_forces();
    const solver::Vertices x = env.collision_positions();
    const std::vector<int>& body = env.model().collision().vertex_body;
    for (int v = 0; v < x.rows(); ++v) {
      const double force = forces.normal.row(v).norm();
      if (!(force > 0.0)) continue;
      ContactPatch& patch =
          body[v] == gripper_.object_body() ? state.object_patch : state.gripper_patch;
      patch.add(v, x.row(v).transpose(), force);
    }
  }

  // How far the object slipped in the gripper since the settled grasp: the distance between
  // where the object's motion carried its settled centre of mass and where the gripper's contact
  // patch, moving as one rigid piece (its best fit), would have carried it. A grasp whose
  // contacts stick moves the object with the patch however the fingers bend, twist or yield on
  // their drives (sag, not slip); a slide or a turn in the fingers moves it away. A soft
  // object's motion is its contact patch's, so that its own sag is not slip either. Without a
  // gripper patch, the centre of mass's displacement.
  double slip(int i) const {
    const solver::EnvironmentHandle& env = engine_->environment(i);
    const TrialState& state = states_[i];
    const Eigen::Vector3d& center = state.settled_center;
    const solver::Vertices x = env.collision_positions();
    const Eigen::Vector3d by_object = gripper_.soft_object() && !state.object_patch.empty()
                                          ? state.object_patch.motion(x)(center)
                                          : env.center_of_mass(gripper_.object_body());
    if (state.gripper_patch.empty()) return (by_object - center).norm();
    return (by_object - state.gripper_patch.motion(x)(center)).norm();
  }

  static std::vector<double> finger_forces(const TrialState& state) {
    std::vector<double> forces;
    for (const FingerServo& f : state.fingers) forces.push_back(f.force());
    return forces;
  }

  // A gravity phase: phase_duration under its gravity, then on until the object is still
  // (still(); the fingers' forces may shift as gravity turns) for settle_steps steps in a row,
  // for at most rest_duration more. The slip is measured where the phase ends, at rest or not
  // (a grasp still swinging on compliant fingers when the wait ends is judged by its slip, as
  // the paper judges every phase); the phase's last frame is that state.
  void shake(int i) {
    solver::EnvironmentHandle& env = engine_->environment(i);
    TrialState& state = states_[i];
    const int object = gripper_.object_body();
    ++state.phase_step;
    for (int j = 0; j < fingers_; ++j) state.fingers[j].observe(finger_force(env, j));
    command(i);
    state.steady_steps = still(i) ? state.steady_steps + 1 : 0;
    state.recent_speed[state.phase_step % TrialOutcome::kEndSpeedSteps] =
        env.center_of_mass_velocity(object).norm();
    const bool full_length = state.phase_step >= steps_per_phase_;
    if (!full_length && state.recorder.validation_due(state.phase_step)) {
      state.recorder.add_validation(frame(i));
    }
    if (!full_length) return;
    const bool at_rest = state.steady_steps >= p_.settle_steps;
    const double slipped = slip(i);
    // An object that has slid kSlidThreshold thresholds is not waited for: it is not swinging
    // back into a hold.
    const bool slid = slipped >= kSlidThreshold * p_.displacement_threshold();
    if (!at_rest && !slid && state.phase_step < max_steps_per_phase_) return;
    state.recorder.add_validation(frame(i));
    io::CandidateRecord& record = state.outcome.result.record;
    const int phase = state.gravity_phase;
    record.displacement[phase] = slipped;
    state.outcome.center_displacement[phase] =
        (env.center_of_mass(object) - state.settled_center).norm();
    state.outcome.end_speed[phase] =
        *std::max_element(state.recent_speed.begin(), state.recent_speed.end());
    record.phase_seconds[phase] = state.phase_step * p_.sim.dt;
    state.phase_step = 0;
    state.steady_steps = 0;
    state.recent_speed.fill(0.0);
    if (!state.decided) decide_at_phase_end(i);
    if (state.decided && !options_.full_trials) return finish(i, *state.decided);
    if (++state.gravity_phase < 6) {
      env.set_gravity(p_.gravity_magnitude * kGravityAxes[state.gravity_phase]);
      return;
    }
    finish(i, state.decided.value_or(io::FailureKind::kNone));
  }

  // The verdict at the end of a gravity phase: the first phase whose object touches no finger
  // any more (dropped: `lost_contact`) or has slipped past the threshold (`displaced`) decides
  // it. No later phase can change it, so the trial stops there unless full_trials asks for the
  // rest (docs/trial.md, "Verdict").
  void decide_at_phase_end(int i) {
    TrialState& state = states_[i];
    const io::CandidateRecord& record = state.outcome.result.record;
    if (!object_touches_gripper(gripper_.object_body(), engine_->environment(i))) {
      state.decided = io::FailureKind::kLostContact;
    } else if (slipped_beyond_threshold(p_, record.displacement, record.phase_seconds,
                                        state.gravity_phase + 1)) {
      state.decided = io::FailureKind::kDisplaced;
    }
  }

  // A failed environment's state is not a grasp (a step may have stopped half-way): its
  // frames end at the last accepted step, and D1/D2 are not measured (NaN). A solver failure
  // after a gravity phase decided the verdict (with full_trials) does not change it;
  // failure_reason keeps the solver's word.
  void fail(int i) {
    TrialState& state = states_[i];
    const solver::EnvironmentHandle& env = engine_->environment(i);
    state.outcome.failure_reason = env.failure();
    io::CandidateRecord& record = state.outcome.result.record;
    if (state.phase == Phase::kClosing) record.closing_forces = finger_forces(state);
    if (!state.metrics_done) {
      record.d1 = record.d2 = std::numeric_limits<double>::quiet_NaN();
    }
    finish(i, state.decided.value_or(solver_failure_kind(env.failure_code())));
  }

  void finish(int i, io::FailureKind failure) {
    TrialState& state = states_[i];
    const solver::EnvironmentHandle& env = engine_->environment(i);
    io::CandidateRecord& record = state.outcome.result.record;
    record.status = failure == io::FailureKind::kNone ? io::Status::kSuccess : io::Status::kFailure;
    record.failure = failure;
    const solver::EnvironmentStatistics& stats = env.statistics();
    record.newton.steps = static_cast<std::uint32_t>(stats.steps);
    record.newton.iterations = static_cast<std::uint32_t>(stats.newton_iterations);
    record.newton.max_iterations = static_cast<std::uint32_t>(stats.max_step_iterations);
    record.newton.retries = static_cast<std::uint32_t>(stats.retries);
    record.simulated_frames = static_cast<std::uint32_t>(state.recorder.simulated_frames());
    state.outcome.steps_by_newton_iterations = stats.steps_by_iterations;
    state.outcome.stage_seconds = env.stage_seconds();
    state.outcome.linear_solves = env.linear_solves();
    std::vector<RecordedFrame> frames = state.recorder.frames();
    if (options_.trajectory) state.outcome.result.trajectory = trajectory_record(frames);
    if (options_.body_frames) {
      for (RecordedFrame& f : frames) state.outcome.body_frames.push_back(std::move(f.bodies));
    }
    state.recorder = FrameRecorder(p_.closing_frames, p_.validation_frames, steps_per_phase_);
    state.phase = Phase::kDone;
    engine_->retire(i);
  }

  const TrialGripper& gripper_;
  const TrialParameters& p_;
  const TrialRunOptions& options_;
  int fingers_ = 0;
  std::unique_ptr<solver::Engine> engine_;
  tbb::task_arena arena_;
  int steps_per_phase_ = 1;
  int max_steps_per_phase_ = 1;  // with the wait for rest
  std::vector<TrialState> states_;
  std::size_t next_ = 0;  // the next candidate to start
  // The collision vertex of each gripper surface vertex, -1 for one that is not (a soft
  // finger's surface is all collision vertices; a link's surface too).
  std::vector<int> gripper_collision_;
};

}  // namespace

std::vector<TrialOutcome> run_protocol(const TrialGripper& gripper,
                                       const TrialRunOptions& options) {
  if (!options.ids.empty() && options.ids.size() != gripper.candidate_count()) {
    throw std::invalid_argument("run_trials: " + std::to_string(options.ids.size()) + " ids for " +
                                std::to_string(gripper.candidate_count()) + " candidates");
  }
  if (options.big_system_solver && options.threads != 1) {
    throw std::invalid_argument("run_trials: a big-system solver needs threads = 1, not " +
                                std::to_string(options.threads));
  }
  if (options.big_system_solver && options.device != solver::EngineDevice::kCpu) {
    throw std::invalid_argument(
        "run_trials: a big-system solver serves the CPU engine's environments, not the "
        "data-parallel engine's");
  }
  ProtocolRunner runner(gripper, options);
  return runner.run();
}

}  // namespace grip::trial
