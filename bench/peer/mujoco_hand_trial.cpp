#include "bench/peer/mujoco_hand_trial.hpp"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "bench/common/cpu_clock.hpp"
#include "bench/peer/mujoco_model.hpp"

namespace grip::bench {

#if GRIP_HAVE_MUJOCO

namespace {

// Contact bits: the object collides with the links, the links not with each other.
constexpr int kLinkBit = 1, kObjectBit = 2;
void write_link_bodies(std::ostringstream& x, const grippers::KinematicTree& tree, int link,
                       double friction, const MujocoSettings& s) {
  const grippers::KinematicLink& l = tree.links()[static_cast<std::size_t>(link)];
  if (l.surface.triangles.rows() > 0) {
    const Eigen::Vector3d lower = l.surface.vertices.colwise().minCoeff();
    const Eigen::Vector3d upper = l.surface.vertices.colwise().maxCoeff();
    const Eigen::Vector3d c = 0.5 * (lower + upper), e = upper - lower;
    const Eigen::Vector3d inertia =
        s.link_mass / 12.0 *
        Eigen::Vector3d(e.y() * e.y() + e.z() * e.z(), e.x() * e.x() + e.z() * e.z(),
                        e.x() * e.x() + e.y() * e.y());
    x << "<inertial pos=\"" << c.x() << ' ' << c.y() << ' ' << c.z() << "\" mass=\"" << s.link_mass
      << "\" diaginertia=\"" << inertia.x() << ' ' << inertia.y() << ' ' << inertia.z()
      << "\"/><geom name=\"link" << link << "\" type=\"mesh\" mesh=\"link" << link
      << "\" contype=\"" << kLinkBit << "\" conaffinity=\"" << kObjectBit << "\" friction=\""
      << friction << " 0.005 0.0001\"/>";
  } else {
    x << "<inertial pos=\"0 0 0\" mass=\"" << s.link_mass << "\" diaginertia=\"1e-6 1e-6 1e-6\"/>";
  }
  for (const grippers::KinematicJoint& j : tree.joints()) {
    if (j.parent_link != link) continue;
    const Eigen::Vector3d& t = j.origin.translation();
    const Eigen::Quaterniond q(j.origin.linear());
    x << "\n<body name=\"link" << j.child_link << "\" pos=\"" << t.x() << ' ' << t.y() << ' '
      << t.z() << "\" quat=\"" << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z() << "\">";
    if (j.type != grippers::JointType::kFixed) {
      x << "<joint name=\"dof" << j.dof << "\" type=\""
        << (j.type == grippers::JointType::kPrismatic ? "slide" : "hinge") << "\" axis=\""
        << j.axis.x() << ' ' << j.axis.y() << ' ' << j.axis.z() << "\" armature=\""
        << s.joint_armature << "\" damping=\"" << s.joint_damping << "\"";
      if (j.type != grippers::JointType::kContinuous) {
        x << " limited=\"true\" range=\"" << j.lower << ' ' << j.upper << "\"";
      }
      x << "/>";
    }
    write_link_bodies(x, tree, j.child_link, friction, s);
    x << "</body>";
  }
}

// The scene as MJCF: the object a free body with one mesh geom, the hand's root link welded to
// the world at the candidate's pose and every other link a body on its joint (body frame = link
// frame), each link one mesh geom (MuJoCo collides the convex hulls of both), each degree of
// freedom a position actuator.
std::string scene_xml(const geometry::SurfaceMesh& object, double density, double friction,
                      const grippers::KinematicTree& tree, const Eigen::Isometry3d& pose,
                      const MujocoSettings& s) {
  std::ostringstream x;
  x << std::setprecision(17);
  x << "<mujoco model=\"peer_hand\">\n<compiler angle=\"radian\"/>\n<option "
       "integrator=\"implicit\" timestep=\""
    << s.timestep
    << "\" gravity=\"0 0 0\"><flag multiccd=\"enable\"/></option>\n<default><geom solref=\""
    << s.contact_time_constant << " 1\" solimp=\"" << s.contact_impedance << ' '
    << s.contact_impedance << " 0.001\"/></default>\n<asset>";
  write_mesh_asset(x, "object", object);
  for (std::size_t l = 0; l < tree.links().size(); ++l) {
    if (tree.links()[l].surface.triangles.rows() == 0) continue;
    x << '\n';
    write_mesh_asset(x, "link" + std::to_string(l), tree.links()[l].surface);
  }
  x << "</asset>\n<worldbody>\n<body name=\"object\"><freejoint name=\"object\"/>"
       "<geom name=\"object\" type=\"mesh\" mesh=\"object\" density=\""
    << density << "\" contype=\"" << kObjectBit << "\" conaffinity=\"" << kLinkBit
    << "\" friction=\"" << friction << " 0.005 0.0001\"/></body>\n";
  const Eigen::Quaterniond q(pose.linear());
  const Eigen::Vector3d& t = pose.translation();
  x << "<body name=\"link0\" pos=\"" << t.x() << ' ' << t.y() << ' ' << t.z() << "\" quat=\""
    << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z() << "\">";
  write_link_bodies(x, tree, 0, friction, s);
  x << "</body>\n</worldbody>\n<actuator>";
  for (int d = 0; d < tree.dof_count(); ++d) {
    x << "<position name=\"dof" << d << "\" joint=\"dof" << d << "\" kp=\"" << s.joint_stiffness
      << "\"/>";
  }
  x << "</actuator>\n</mujoco>\n";
  return x.str();
}

// A finger's drive: its travel along its closing path (HandTrialScene::closing_direction, the
// path grip's trial follows), which sets its joints' position targets.
struct FingerDrive {
  Eigen::VectorXd direction;
  double end = 0.0;     // the travel at which a joint reaches its limit
  double travel = 0.0;  // m, of the path's fastest pushed point
  bool touched = false;
  bool stopped = false;
  double force = 0.0;  // N, normal, with the object, mean over the last grip step
};

class HandSimulation {
 public:
  HandSimulation(mjModel* m, mjData* d, const trial::HandTrialScene& scene,
                 const trial::HandTrialGrasp& grasp, const trial::TrialParameters& p,
                 const MujocoSettings& s)
      : m_(m), d_(d), scene_(scene), grasp_(grasp), p_(p), s_(s) {
    const grippers::KinematicTree& tree = scene.kinematics();
    object_body_ = mj_name2id(m, mjOBJ_BODY, "object");
    object_geom_ = mj_name2id(m, mjOBJ_GEOM, "object");
    const int joint = m->body_jntadr[object_body_];
    object_qpos_ = m->jnt_qposadr[joint];
    object_dof_ = m->jnt_dofadr[joint];
    link_body_.resize(tree.links().size());
    body_finger_.assign(static_cast<std::size_t>(m->nbody), -2);  // -2: not a link
    for (std::size_t l = 0; l < tree.links().size(); ++l) {
      link_body_[l] = mj_name2id(m, mjOBJ_BODY, ("link" + std::to_string(l)).c_str());
      body_finger_[static_cast<std::size_t>(link_body_[l])] = -1;  // the palm
    }
    for (std::size_t f = 0; f < scene.fingers().size(); ++f) {
      for (const int l : scene.fingers()[f].links) {
        body_finger_[static_cast<std::size_t>(link_body_[static_cast<std::size_t>(l)])] =
            static_cast<int>(f);
      }
      FingerDrive drive;
      drive.direction = scene.closing_direction(grasp, static_cast<int>(f));
      drive.end = scene.closing_travel(grasp.joints, drive.direction, static_cast<int>(f));
      drives_.push_back(std::move(drive));
    }
    for (int dof = 0; dof < tree.dof_count(); ++dof) {
      const std::string name = "dof" + std::to_string(dof);
      const int j = mj_name2id(m, mjOBJ_JOINT, name.c_str());
      dof_actuator_.push_back(mj_name2id(m, mjOBJ_ACTUATOR, name.c_str()));
      d->qpos[m->jnt_qposadr[j]] = grasp.joints[dof];
      d->ctrl[dof_actuator_.back()] = grasp.joints[dof];
    }
    mj_forward(m, d);
    std::copy(d->qpos + object_qpos_, d->qpos + object_qpos_ + 7, held_.begin());
  }

  MujocoHandOutcome run() {
    MujocoHandOutcome out;
    const double tolerance = p_.force_tolerance * p_.grip_force;
    // Closing, the object held where the candidate found it, gravity off: each finger moves
    // along its path at approach_speed until it first touches the object, then at
    // squeeze_speed, and stops (its joint targets held) once its normal force with the object
    // reaches the grip force less the tolerance, or its path ends. Once every finger has
    // stopped, the object is released. (grip's fingers servo their force onto the grip force;
    // here a finger that overshoots keeps its force.)
    double longest = 0.0;
    for (const FingerDrive& f : drives_) longest = std::max(longest, f.end);
    const double closing_time =
        longest / s_.approach_speed + s_.closing_margin + p_.settle_max_steps * p_.sim.dt;
    const long closing_windows = std::lround(closing_time / p_.sim.dt);
    bool closed = false;
    for (long k = 0; k < closing_windows && !closed; ++k) {
      if (!window(Eigen::Vector3d::Zero(), true)) return unstable(out);
      closed = true;
      for (FingerDrive& f : drives_) {
        f.touched = f.touched || f.force > 0.0;
        f.stopped = f.stopped || f.force >= p_.grip_force - tolerance || f.travel >= f.end;
        if (f.stopped) continue;
        closed = false;
        const double speed = f.touched ? p_.squeeze_speed : s_.approach_speed;
        f.travel = std::min(f.travel + speed * p_.sim.dt, f.end);
      }
      drive();
    }
    if (!closed) {
      out.verdict = "unsettled";
      out.message = fmt::format("closing: finger forces {} N after {:.2f} s", forces_text(),
                                closing_windows * p_.sim.dt);
      return finish(out);
    }
    // Settling: released, gravity off, the fingers held at their targets (springs of the servo's
    // gain), grip's rule over grip steps: the object's speed and turning rate below settle_speed
    // and settle_angular_speed, and no finger's force changing by more than the tolerance,
    // settle_steps steps in a row, within settle_max_steps; no_contact once nothing touches it.
    int steady = 0;
    double speed = 0.0, turning = 0.0;
    for (int k = 0; k < p_.settle_max_steps && steady < p_.settle_steps; ++k) {
      const Eigen::Vector3d center = object_center();
      const Eigen::Quaterniond turn = object_rotation();
      std::vector<double> before;
      for (const FingerDrive& f : drives_) before.push_back(f.force);
      if (!window(Eigen::Vector3d::Zero(), false)) return unstable(out);
      if (!touching_) {
        out.verdict = "no_contact";
        return finish(out);
      }
      speed = (object_center() - center).norm() / p_.sim.dt;
      turning = turn.angularDistance(object_rotation()) / p_.sim.dt;
      bool still = speed < p_.settle_speed && turning < p_.settle_angular_speed;
      for (std::size_t f = 0; f < drives_.size(); ++f) {
        still = still && std::abs(drives_[f].force - before[f]) <= tolerance;
      }
      steady = still ? steady + 1 : 0;
    }
    if (steady < p_.settle_steps) {
      out.verdict = "unsettled";
      out.message = fmt::format("settling: object at {:.2g} m/s, {:.2g} rad/s, finger forces {} N",
                                speed, turning, forces_text());
      return finish(out);
    }
    out.settled = true;
    for (const FingerDrive& f : drives_) out.closing_forces.push_back(f.force);
    out.object = body_pose(d_, object_body_);
    out.links = link_poses();
    // The gravity test: slip is the centre of mass's displacement less the force-weighted mean
    // displacement of the contact points on the links (grip's contact patch, carried by them).
    record_patch();
    const Eigen::Vector3d center = object_center();
    const long phase_windows = std::lround(p_.phase_duration / p_.sim.dt);
    // Each phase's slip and length, judged by the trial's own verdict rule.
    std::array<double, 6> slip{};
    std::array<double, 6> seconds{};
    for (std::size_t phase = 0; phase < trial::kGravityAxes.size(); ++phase) {
      const Eigen::Vector3d g = p_.gravity_magnitude * trial::kGravityAxes[phase];
      for (long k = 0; k < phase_windows; ++k) {
        if (!window(g, false)) return unstable(out);
      }
      slip[phase] = (object_center() - center - patch_moved()).norm();
      seconds[phase] = static_cast<double>(phase_windows) * p_.sim.dt;
      out.largest_slip = std::max(out.largest_slip, slip[phase]);
    }
    out.verdict = !touching_                                           ? "lost_contact"
                  : trial::slipped_beyond_threshold(p_, slip, seconds) ? "displaced"
                                                                       : "success";
    return finish(out);
  }

  // MuJoCo's deepest contact between object and a link over every step so far (m).
  double deepest_penetration() const { return deepest_penetration_; }

 private:
  struct PatchPoint {
    int body;
    Eigen::Vector3d local;    // in the body's frame
    Eigen::Vector3d settled;  // world, at the settled grasp
    double weight;            // N
  };

  // The fingers' joint targets from their travels.
  void drive() {
    for (std::size_t f = 0; f < drives_.size(); ++f) {
      const int finger = static_cast<int>(f);
      const Eigen::VectorXd q =
          scene_.finger_joints(grasp_.joints, drives_[f].direction, finger, drives_[f].travel);
      for (const int dof : scene_.fingers()[f].dofs) d_->ctrl[dof_actuator_[dof]] = q[dof];
    }
  }

  // One grip step (p.sim.dt) of MuJoCo steps: each finger's force its mean over them,
  // touching_ whether the object touched a link at the last.
  bool window(const Eigen::Vector3d& g, bool hold) {
    const long n = std::max(1L, std::lround(p_.sim.dt / s_.timestep));
    for (FingerDrive& f : drives_) f.force = 0.0;
    std::vector<double> forces(drives_.size());
    for (long k = 0; k < n; ++k) {
      if (!step(g, hold)) return false;
      finger_forces(forces);
      for (std::size_t f = 0; f < drives_.size(); ++f) {
        drives_[f].force += forces[f] / static_cast<double>(n);
      }
    }
    return true;
  }

  bool step(const Eigen::Vector3d& g, bool hold) {
    for (int k = 0; k < 3; ++k) m_->opt.gravity[k] = g[k];
    for (const int b : link_body_) {
      for (int k = 0; k < 3; ++k) d_->xfrc_applied[6 * b + k] = -m_->body_mass[b] * g[k];
    }
    mj_step(m_, d_);
    for (int c = 0; c < d_->ncon; ++c) {
      if (link_of(d_->contact[c]) >= 0) {
        deepest_penetration_ = std::max(deepest_penetration_, -d_->contact[c].dist);
      }
    }
    if (hold) {
      std::copy(held_.begin(), held_.end(), d_->qpos + object_qpos_);
      std::fill(d_->qvel + object_dof_, d_->qvel + object_dof_ + 6, 0.0);
    }
    return d_->warning[mjWARN_BADQACC].number == 0;
  }

  // The link's body of `contact` if it is between the object and a link, else -1.
  int link_of(const mjContact& contact) const {
    int other = -1;
    if (contact.geom[0] == object_geom_) other = contact.geom[1];
    if (contact.geom[1] == object_geom_) other = contact.geom[0];
    if (other < 0) return -1;
    const int body = m_->geom_bodyid[other];
    return body_finger_[static_cast<std::size_t>(body)] == -2 ? -1 : body;
  }

  // link_of contact c, its normal force in `normal`.
  int link_contact(int c, double& normal) const {
    const int body = link_of(d_->contact[c]);
    if (body < 0) return -1;
    mjtNum f[6];
    mj_contactForce(m_, d_, c, f);
    normal = f[0];
    return body;
  }

  // Each finger's normal force with the object now (grip's finger force: the pairs' normal
  // forces summed over the finger's links); sets touching_.
  void finger_forces(std::vector<double>& forces) {
    std::fill(forces.begin(), forces.end(), 0.0);
    touching_ = false;
    for (int c = 0; c < d_->ncon; ++c) {
      double normal = 0.0;
      const int body = link_contact(c, normal);
      if (body < 0) continue;
      touching_ = touching_ || normal > 0.0;
      const int finger = body_finger_[static_cast<std::size_t>(body)];
      if (finger >= 0) forces[static_cast<std::size_t>(finger)] += normal;
    }
  }

  void record_patch() {
    patch_.clear();
    for (int c = 0; c < d_->ncon; ++c) {
      double normal = 0.0;
      const int body = link_contact(c, normal);
      if (body < 0 || normal <= 0.0) continue;
      const Eigen::Vector3d at = Eigen::Map<const Eigen::Vector3d>(d_->contact[c].pos);
      patch_.push_back({body, body_pose(d_, body).inverse() * at, at, normal});
    }
  }

  Eigen::Vector3d patch_moved() const {
    Eigen::Vector3d moved = Eigen::Vector3d::Zero();
    double weight = 0.0;
    for (const PatchPoint& p : patch_) {
      moved += p.weight * (body_pose(d_, p.body) * p.local - p.settled);
      weight += p.weight;
    }
    return weight > 0.0 ? Eigen::Vector3d(moved / weight) : Eigen::Vector3d::Zero();
  }

  std::vector<Eigen::Isometry3d> link_poses() const {
    std::vector<Eigen::Isometry3d> poses;
    for (const int b : link_body_) poses.push_back(body_pose(d_, b));
    return poses;
  }

  std::string forces_text() const {
    std::string text;
    for (const FingerDrive& f : drives_)
      text += (text.empty() ? "" : ", ") + fmt::format("{:.1f}", f.force);
    return text;
  }

  Eigen::Vector3d object_center() const {
    return Eigen::Map<const Eigen::Vector3d>(d_->xipos + 3 * object_body_);
  }
  Eigen::Quaterniond object_rotation() const {
    const mjtNum* q = d_->xquat + 4 * object_body_;
    return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
  }

  MujocoHandOutcome& finish(MujocoHandOutcome& out) const {
    out.final_object = body_pose(d_, object_body_);
    out.final_links = link_poses();
    if (!out.settled) {
      out.object = out.final_object;
      out.links = out.final_links;
    }
    return out;
  }

  MujocoHandOutcome& unstable(MujocoHandOutcome& out) const {
    out.verdict = "numerical";
    out.message = "MuJoCo: unstable simulation (bad qacc), state reset";
    return finish(out);
  }

  mjModel* m_;  // its gravity changes per phase
  mjData* d_;
  const trial::HandTrialScene& scene_;
  const trial::HandTrialGrasp& grasp_;
  const trial::TrialParameters& p_;
  const MujocoSettings& s_;
  int object_body_ = -1, object_geom_ = -1, object_qpos_ = -1, object_dof_ = -1;
  double deepest_penetration_ = 0.0;
  std::vector<int> link_body_;     // per kinematic link
  std::vector<int> body_finger_;   // per MuJoCo body: its finger, -1 the palm, -2 not a link
  std::vector<int> dof_actuator_;  // per degree of freedom
  std::vector<FingerDrive> drives_;
  std::vector<PatchPoint> patch_;
  bool touching_ = false;
  std::array<mjtNum, 7> held_{};
};

}  // namespace

MujocoHandOutcome run_mujoco_hand_trial(const geometry::SurfaceMesh& object, double density,
                                        double friction, const trial::HandTrialScene& scene,
                                        const trial::HandTrialGrasp& grasp,
                                        const trial::TrialParameters& parameters,
                                        const MujocoSettings& settings) {
  scene.check(grasp);
  const double start = process_cpu_seconds();
  std::string message;
  mjModel* m = load_model(
      scene_xml(object, density, friction, scene.kinematics(), grasp.pose, settings), message);
  if (!m) {
    MujocoHandOutcome out;
    out.verdict = "load_error";
    out.message = "MuJoCo: " + message;
    return out;
  }
  mjData* d = mj_makeData(m);
  const double compiled = process_cpu_seconds();
  HandSimulation simulation(m, d, scene, grasp, parameters, settings);
  MujocoHandOutcome out = simulation.run();
  out.deepest_penetration = simulation.deepest_penetration();
  out.compile_cpu_seconds = compiled - start;
  out.cpu_seconds = process_cpu_seconds() - compiled;
  mj_deleteData(d);
  mj_deleteModel(m);
  return out;
}

#else  // without MuJoCo

MujocoHandOutcome run_mujoco_hand_trial(const geometry::SurfaceMesh&, double, double,
                                        const trial::HandTrialScene&, const trial::HandTrialGrasp&,
                                        const trial::TrialParameters&, const MujocoSettings&) {
  MujocoHandOutcome out;
  out.verdict = "load_error";
  out.message = "this build has no MuJoCo (scripts/install-peers.sh, then configure again)";
  return out;
}

#endif

}  // namespace grip::bench
