#include "bench/peer/mujoco_trial.hpp"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "bench/common/cpu_clock.hpp"
#include "bench/peer/mujoco_model.hpp"

namespace grip::bench {

#if GRIP_HAVE_MUJOCO

bool mujoco_available() { return true; }
std::string mujoco_version() { return mj_versionString(); }

namespace {

using grippers::Jaw;
constexpr std::array<Jaw, 2> kJaws = {Jaw::kPositive, Jaw::kNegative};

// The scene as MJCF: the object a free body with one mesh geom (MuJoCo collides its convex
// hull), each jaw a box body on a slide joint along its closing path, driven by a position
// actuator whose force saturates at the grip force, its speed limited to squeeze_speed by
// joint damping (grip_force / squeeze_speed). multiccd gives a face-face contact several points.
std::string scene_xml(const geometry::SurfaceMesh& object, double density, double friction,
                      const grippers::ParallelGripper& gripper, const Eigen::Isometry3d& pose,
                      double opening, const trial::TrialParameters& p, const MujocoSettings& s) {
  std::ostringstream x;
  x << std::setprecision(17);
  x << "<mujoco model=\"peer\">\n<option timestep=\"" << s.timestep
    << "\" gravity=\"0 0 0\"><flag multiccd=\"enable\"/></option>\n<default><geom solref=\""
    << s.contact_time_constant << " 1\" solimp=\"" << s.contact_impedance << ' '
    << s.contact_impedance << " 0.001\"/></default>\n<asset>";
  write_mesh_asset(x, "object", object);
  x << "</asset>\n<worldbody>\n<body name=\"object\"><freejoint name=\"object\"/>"
       "<geom name=\"object\" type=\"mesh\" mesh=\"object\" density=\""
    << density << "\" friction=\"" << friction << " 0.005 0.0001\"/></body>\n";
  const Eigen::Vector3d lower = gripper.finger_surface.vertices.colwise().minCoeff();
  const Eigen::Vector3d upper = gripper.finger_surface.vertices.colwise().maxCoeff();
  const Eigen::Vector3d center = 0.5 * (lower + upper), half = 0.5 * (upper - lower);
  const double travel = std::max(1e-6, 0.5 * (opening - p.final_opening));
  for (int j = 0; j < 2; ++j) {
    const Eigen::Isometry3d finger = pose * gripper.finger_pose(kJaws[j], opening);
    const Eigen::Quaterniond q(finger.linear());
    const Eigen::Vector3d closing =
        (kJaws[j] == Jaw::kPositive ? -1.0 : 1.0) * pose.linear().col(1);
    const Eigen::Vector3d axis = finger.linear().transpose() * closing;
    const Eigen::Vector3d& t = finger.translation();
    x << "<body name=\"jaw" << j << "\" pos=\"" << t.x() << ' ' << t.y() << ' ' << t.z()
      << "\" quat=\"" << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z() << "\">"
      << "<joint name=\"jaw" << j << "\" type=\"slide\" axis=\"" << axis.x() << ' ' << axis.y()
      << ' ' << axis.z() << "\" limited=\"true\" range=\"0 " << travel << "\" damping=\""
      << p.grip_force / p.squeeze_speed << "\"/><geom name=\"jaw" << j << "\" type=\"box\" size=\""
      << half.x() << ' ' << half.y() << ' ' << half.z() << "\" pos=\"" << center.x() << ' '
      << center.y() << ' ' << center.z() << "\" mass=\"" << s.jaw_mass << "\" friction=\""
      << friction << " 0.005 0.0001\"/></body>\n";
  }
  x << "</worldbody>\n<contact><exclude body1=\"jaw0\" body2=\"jaw1\"/></contact>\n<actuator>";
  for (int j = 0; j < 2; ++j) {
    x << "<position name=\"jaw" << j << "\" joint=\"jaw" << j
      << "\" kp=\"1e5\" forcelimited=\"true\" forcerange=\"" << -p.grip_force << ' ' << p.grip_force
      << "\"/>";
  }
  x << "</actuator>\n</mujoco>\n";
  return x.str();
}

// One trial's simulation over a compiled model.
class Simulation {
 public:
  Simulation(mjModel* m, mjData* d, const trial::TrialParameters& p, const MujocoSettings& s)
      : m_(m), d_(d), p_(p), s_(s) {
    object_body_ = mj_name2id(m, mjOBJ_BODY, "object");
    object_geom_ = mj_name2id(m, mjOBJ_GEOM, "object");
    const int joint = m->body_jntadr[object_body_];
    object_qpos_ = m->jnt_qposadr[joint];
    object_dof_ = m->jnt_dofadr[joint];
    for (int j = 0; j < 2; ++j) {
      const std::string name = "jaw" + std::to_string(j);
      jaw_body_[j] = mj_name2id(m, mjOBJ_BODY, name.c_str());
      jaw_geom_[j] = mj_name2id(m, mjOBJ_GEOM, name.c_str());
      const int jaw_joint = mj_name2id(m, mjOBJ_JOINT, name.c_str());
      jaw_qpos_[j] = m->jnt_qposadr[jaw_joint];
      jaw_joint_[j] = jaw_joint;
      travel_[j] = m->jnt_range[2 * jaw_joint + 1];
      d->ctrl[mj_name2id(m, mjOBJ_ACTUATOR, name.c_str())] = travel_[j] + 0.01;  // saturated
    }
    mj_forward(m, d);
    std::copy(d->qpos + object_qpos_, d->qpos + object_qpos_ + 7, held_.begin());
  }

  MujocoOutcome run() {
    MujocoOutcome out;
    const double force_tolerance = p_.force_tolerance * p_.grip_force;
    // A jaw is force-driven: it rests once its drive (grip_force) is balanced by the object (or
    // its path's end), to within the protocol's force tolerance, i.e. once its damping force
    // is below the tolerance. That stands for grip's "within tolerance of grip_force": the
    // object's normal force alone is not the balance here, since friction on a curved or
    // side-on contact takes part of the drive.
    const double rest_speed = force_tolerance / (p_.grip_force / p_.squeeze_speed);
    // Closing: the object held where the candidate found it, gravity off, until both jaws rest.
    const double closing_time =
        std::max(travel_[0], travel_[1]) / p_.squeeze_speed + s_.closing_margin;
    const long closing_windows = std::lround(closing_time / p_.sim.dt);
    bool closed = false;
    for (long k = 0; k < closing_windows && !closed; ++k) {
      if (!window(Eigen::Vector3d::Zero(), true)) return unstable(out);
      closed = jaw_speed_[0] <= rest_speed && jaw_speed_[1] <= rest_speed;
    }
    if (!closed) {
      out.verdict = "unsettled";
      out.message = fmt::format("closing: jaw forces {:.1f} N, {:.1f} N after {:.2f} s",
                                mean_force_[0], mean_force_[1], closing_windows * p_.sim.dt);
      return out;
    }
    // Settling: released, gravity off, grip's rule over grip steps: the object's mean speed and
    // turning rate below settle_speed and settle_angular_speed, and no jaw's mean force changing
    // by more than the tolerance, settle_steps steps in a row, within settle_max_steps. Grip's
    // rigid jaws are springs at rest by then; MuJoCo's still creep into the softer contact of a
    // released object, so both must also rest, as closing requires.
    int steady = 0;
    double speed = 0.0, turning = 0.0;
    for (int k = 0; k < p_.settle_max_steps && steady < p_.settle_steps; ++k) {
      const Eigen::Vector3d center = object_center();
      const Eigen::Quaterniond turn = object_rotation();
      const std::array<double, 2> before = mean_force_;
      if (!window(Eigen::Vector3d::Zero(), false)) return unstable(out);
      speed = (object_center() - center).norm() / p_.sim.dt;
      turning = turn.angularDistance(object_rotation()) / p_.sim.dt;
      bool still = speed < p_.settle_speed && turning < p_.settle_angular_speed;
      for (int j = 0; j < 2; ++j) {
        still = still && std::abs(mean_force_[j] - before[j]) <= force_tolerance &&
                jaw_speed_[j] <= rest_speed;
      }
      steady = still ? steady + 1 : 0;
    }
    if (steady < p_.settle_steps) {
      out.verdict = "unsettled";
      out.message =
          fmt::format("settling: object at {:.2g} m/s, {:.2g} rad/s, jaw forces {:.1f} N, {:.1f} N",
                      speed, turning, mean_force_[0], mean_force_[1]);
      return out;
    }
    out.settled = true;
    out.closing_forces = mean_force_;
    out.object = body_pose(d_, object_body_);
    for (int j = 0; j < 2; ++j) out.fingers[j] = body_pose(d_, jaw_body_[j]);
    if (!touching_) {
      out.verdict = "no_contact";
      return out;
    }
    // The gravity test: slip is the centre of mass's displacement less the force-weighted mean
    // displacement of the jaws (grip's contact patch: a rigid jaw's points move with it).
    const Eigen::Vector3d center = object_center();
    const double total = mean_force_[0] + mean_force_[1];
    const std::array<double, 2> weight = {mean_force_[0] / total, mean_force_[1] / total};
    const long phase_windows = std::lround(p_.phase_duration / p_.sim.dt);
    // Each phase's slip and length, judged by the trial's own verdict rule.
    std::array<double, 6> slip{};
    std::array<double, 6> seconds{};
    for (std::size_t phase = 0; phase < trial::kGravityAxes.size(); ++phase) {
      const Eigen::Vector3d g = p_.gravity_magnitude * trial::kGravityAxes[phase];
      for (long k = 0; k < phase_windows; ++k) {
        if (!window(g, false)) return unstable(out);
      }
      Eigen::Vector3d patch = Eigen::Vector3d::Zero();
      for (int j = 0; j < 2; ++j) {
        patch +=
            weight[j] * (body_pose(d_, jaw_body_[j]).translation() - out.fingers[j].translation());
      }
      slip[phase] = (object_center() - center - patch).norm();
      seconds[phase] = static_cast<double>(phase_windows) * p_.sim.dt;
      out.largest_slip = std::max(out.largest_slip, slip[phase]);
    }
    out.verdict = !touching_                                           ? "lost_contact"
                  : trial::slipped_beyond_threshold(p_, slip, seconds) ? "displaced"
                                                                       : "success";
    return out;
  }

 private:
  // One grip step (p.sim.dt) of MuJoCo steps; mean_force_ and jaw_speed_ are each jaw's mean
  // force and speed over it,
  // touching_ whether the object touched a jaw at its last step. MuJoCo's contacts chatter from
  // step to step (contact points come and go); grip's step is what the protocol's rates and
  // forces are measured over.
  bool window(const Eigen::Vector3d& g, bool hold) {
    const long n = std::max(1L, std::lround(p_.sim.dt / s_.timestep));
    const std::array<double, 2> start = {d_->qpos[jaw_qpos_[0]], d_->qpos[jaw_qpos_[1]]};
    mean_force_ = {0.0, 0.0};
    for (long k = 0; k < n; ++k) {
      if (!step(g, hold)) return false;
      touching_ = false;
      for (int j = 0; j < 2; ++j) mean_force_[j] += jaw_force(j) / static_cast<double>(n);
    }
    for (int j = 0; j < 2; ++j) {
      jaw_speed_[j] = std::abs(d_->qpos[jaw_qpos_[j]] - start[j]) / (n * s_.timestep);
    }
    return true;
  }

  Eigen::Vector3d object_center() const {
    return Eigen::Map<const Eigen::Vector3d>(d_->xipos + 3 * object_body_);
  }
  Eigen::Quaterniond object_rotation() const {
    const mjtNum* q = d_->xquat + 4 * object_body_;
    return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
  }

  // One step under gravity `g`, the jaws' weight compensated; false if MuJoCo found the state
  // unstable (it resets it).
  bool step(const Eigen::Vector3d& g, bool hold) {
    for (int k = 0; k < 3; ++k) m_->opt.gravity[k] = g[k];
    for (int j = 0; j < 2; ++j) {
      for (int k = 0; k < 3; ++k) {
        d_->xfrc_applied[6 * jaw_body_[j] + k] = -m_->body_mass[jaw_body_[j]] * g[k];
      }
    }
    mj_step(m_, d_);
    if (hold) {
      std::copy(held_.begin(), held_.end(), d_->qpos + object_qpos_);
      std::fill(d_->qvel + object_dof_, d_->qvel + object_dof_ + 6, 0.0);
    }
    return d_->warning[mjWARN_BADQACC].number == 0;
  }

  // The object's contact force on jaw j along the jaw's opening direction (N), normal and
  // friction together: what the jaw's drive works against, the grip force once the jaw rests.
  // A curved surface met off the axis pushes back with less normal force than that, and
  // friction takes the rest. Sets touching_ on any positive normal force.
  double jaw_force(int j) {
    const Eigen::Map<const Eigen::Vector3d> closing(d_->xaxis + 3 * jaw_joint_[j]);
    double sum = 0.0;
    for (int c = 0; c < d_->ncon; ++c) {
      const mjContact& contact = d_->contact[c];
      const bool jaw_second = contact.geom[1] == jaw_geom_[j];
      if (!((contact.geom[0] == object_geom_ && jaw_second) ||
            (contact.geom[1] == object_geom_ && contact.geom[0] == jaw_geom_[j]))) {
        continue;
      }
      mjtNum f[6];
      mj_contactForce(m_, d_, c, f);  // in the contact frame: normal, two tangents
      const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> frame(contact.frame);
      const Eigen::Vector3d on_second = frame.transpose() * Eigen::Vector3d(f[0], f[1], f[2]);
      sum -= (jaw_second ? on_second : -on_second).dot(closing);
      touching_ = touching_ || f[0] > 0.0;
    }
    return sum;
  }

  MujocoOutcome& unstable(MujocoOutcome& out) const {
    out.verdict = "numerical";
    out.message = "MuJoCo: unstable simulation (bad qacc), state reset";
    return out;
  }

  mjModel* m_;  // its gravity changes per phase
  mjData* d_;
  const trial::TrialParameters& p_;
  const MujocoSettings& s_;
  int object_body_ = -1, object_geom_ = -1, object_qpos_ = -1, object_dof_ = -1;
  std::array<int, 2> jaw_body_{}, jaw_geom_{}, jaw_qpos_{};
  std::array<double, 2> travel_{};
  std::array<int, 2> jaw_joint_{};
  std::array<double, 2> mean_force_{};
  std::array<double, 2> jaw_speed_{};  // m/s
  bool touching_ = false;
  std::array<mjtNum, 7> held_{};
};

}  // namespace

MujocoOutcome run_mujoco_trial(const geometry::SurfaceMesh& object, double density, double friction,
                               const grippers::ParallelGripper& gripper,
                               const Eigen::Isometry3d& pose, double opening,
                               const trial::TrialParameters& parameters,
                               const MujocoSettings& settings) {
  const double start = process_cpu_seconds();
  std::string message;
  mjModel* m = load_model(
      scene_xml(object, density, friction, gripper, pose, opening, parameters, settings), message);
  if (!m) {
    MujocoOutcome out;
    out.verdict = "load_error";
    out.message = "MuJoCo: " + message;
    return out;
  }
  mjData* d = mj_makeData(m);
  const double compiled = process_cpu_seconds();
  MujocoOutcome out = Simulation(m, d, parameters, settings).run();
  out.compile_cpu_seconds = compiled - start;
  out.cpu_seconds = process_cpu_seconds() - compiled;
  mj_deleteData(d);
  mj_deleteModel(m);
  return out;
}

#else  // without MuJoCo

bool mujoco_available() { return false; }
std::string mujoco_version() { return ""; }

MujocoOutcome run_mujoco_trial(const geometry::SurfaceMesh&, double, double,
                               const grippers::ParallelGripper&, const Eigen::Isometry3d&, double,
                               const trial::TrialParameters&, const MujocoSettings&) {
  MujocoOutcome out;
  out.verdict = "load_error";
  out.message = "this build has no MuJoCo (scripts/install-peers.sh, then configure again)";
  return out;
}

#endif

}  // namespace grip::bench
