#include "bench/peer/mujoco_trial.hpp"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "bench/common/cpu_clock.hpp"
#include "bench/peer/mujoco_model.hpp"
#include "src/geometry/tet_quality.hpp"
#include "src/trial/contact_patch.hpp"

namespace grip::bench {

#if GRIP_HAVE_MUJOCO

bool mujoco_available() { return true; }
std::string mujoco_version() { return mj_versionString(); }

namespace {

using grippers::Jaw;

// MuJoCo's flex vertex positions, in place (rows: vertices).
using FlexVertices = Eigen::Map<const geometry::Vertices>;

// The tets of `mesh` whose signed volume at `x` is not positive.
int inverted_tets(const geometry::TetMesh& mesh, const FlexVertices& x) {
  int inverted = 0;
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) {
    Eigen::Matrix3d edges;  // from the tet's first vertex to the others
    for (int k = 0; k < 3; ++k) {
      edges.col(k) = (x.row(mesh.tets(t, k + 1)) - x.row(mesh.tets(t, 0))).transpose();
    }
    if (!(edges.determinant() > 0.0)) ++inverted;
  }
  return inverted;
}
constexpr std::array<Jaw, 2> kJaws = {Jaw::kPositive, Jaw::kNegative};

// A rigid jaw's finger: one box geom over the finger's bounding box, of the jaw's mass.
void write_box_finger(std::ostream& x, int j, const grippers::ParallelGripper& gripper,
                      double friction, const MujocoSettings& s) {
  const Eigen::Vector3d lower = gripper.finger_surface.vertices.colwise().minCoeff();
  const Eigen::Vector3d upper = gripper.finger_surface.vertices.colwise().maxCoeff();
  const Eigen::Vector3d center = 0.5 * (lower + upper), half = 0.5 * (upper - lower);
  x << "<geom name=\"jaw" << j << "\" type=\"box\" size=\"" << half.x() << ' ' << half.y() << ' '
    << half.z() << "\" pos=\"" << center.x() << ' ' << center.y() << ' ' << center.z()
    << "\" mass=\"" << s.jaw_mass << "\" friction=\"" << friction << " 0.005 0.0001\"/>";
}

// A soft finger at `pose` (world from finger frame): a 3D flex of the finger's tets (they
// collide and carry the elasticity: Saint Venant-Kirchhoff of grip's E and nu, with its Rayleigh
// damping), moved by a trilinear field over MuJoCo's cells (MujocoSettings::flex_cells). Contact
// types let a finger touch the object only (contype 1, conaffinity 2; the object 2 and 1).
void write_flex_finger(std::ostream& x, int j, const grippers::FinRayFinger& finger,
                       const Eigen::Isometry3d& pose, double friction, const MujocoSettings& s) {
  const geometry::TetMesh& mesh = finger.mesh;
  const double mass = finger.material.density * geometry::tet_quality(mesh).total_volume;
  const Eigen::Quaterniond q(pose.linear());
  const Eigen::Vector3d& t = pose.translation();
  x << "<flexcomp name=\"finger" << j << "\" pos=\"" << t.x() << ' ' << t.y() << ' ' << t.z()
    << "\" quat=\"" << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z()
    << "\" type=\"direct\" dim=\"3\" dof=\"trilinear\" cellcount=\"" << s.flex_cells[0] << ' '
    << s.flex_cells[1] << ' ' << s.flex_cells[2] << "\" radius=\"0\" mass=\"" << mass
    << "\" point=\"";
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    x << mesh.vertices(v, 0) << ' ' << mesh.vertices(v, 1) << ' ' << mesh.vertices(v, 2) << ' ';
  }
  x << "\" element=\"";
  for (Eigen::Index e = 0; e < mesh.tets.rows(); ++e) {
    x << mesh.tets(e, 0) << ' ' << mesh.tets(e, 1) << ' ' << mesh.tets(e, 2) << ' '
      << mesh.tets(e, 3) << ' ';
  }
  x << "\"><contact condim=\"3\" selfcollide=\"none\" contype=\"1\" conaffinity=\"2\" friction=\""
    << friction << " 0.005 0.0001\" solref=\"" << s.flex_contact_time_constant << " 1\" solimp=\""
    << s.flex_contact_impedance << ' ' << s.flex_contact_impedance
    << " 0.001\"/><elasticity young=\"" << finger.material.youngs_modulus << "\" poisson=\""
    << finger.material.poisson_ratio << "\" damping=\"" << finger.material.damping
    << "\"/></flexcomp>\n";
}

// Each soft finger's mount: its nodes on the mount face (z = 0; flexcomp names a node
// FLEX_i_j_k by its grid indices) held to its jaw by stiff connect constraints. MuJoCo's own pin
// would make the nodes the jaw's children, and then the jaw's joint sees only the pinned nodes'
// elastic reaction, not the others': half the drive reached the object.
void write_flex_mounts(std::ostream& x, const MujocoSettings& s) {
  x << "<equality>";
  for (int j = 0; j < 2; ++j) {
    for (int a = 0; a <= s.flex_cells[0]; ++a) {
      for (int b = 0; b <= s.flex_cells[1]; ++b) {
        x << "<connect body1=\"finger" << j << '_' << a << '_' << b << "_0\" body2=\"jaw" << j
          << "\" anchor=\"0 0 0\" solref=\"" << s.flex_contact_time_constant << " 1\" solimp=\""
          << s.flex_contact_impedance << ' ' << s.flex_contact_impedance << " 0.001\"/>";
      }
    }
  }
  x << "</equality>\n";
}

// The scene as MJCF: the object a free body with one mesh geom (MuJoCo collides its convex
// hull), each jaw a body on a slide joint along its closing path, pushed by a motor of the grip
// force, its speed limited to squeeze_speed by joint damping (grip_force / squeeze_speed),
// carrying a box (rigid jaws) or holding a flex's mount (soft fingers). multiccd gives a
// face-face contact several points. Soft fingers step with MuJoCo's discrete integrator, the one
// that integrates flex elasticity with vertices attached to moving bodies.
std::string scene_xml(const geometry::SurfaceMesh& object, double density, double friction,
                      const grippers::ParallelGripper& gripper, const Eigen::Isometry3d& pose,
                      double opening, const trial::TrialParameters& p, const MujocoSettings& s) {
  std::ostringstream x;
  x << std::setprecision(17);
  const bool soft = gripper.soft_finger.has_value();
  const double time_constant = soft ? s.flex_contact_time_constant : s.contact_time_constant;
  const double impedance = soft ? s.flex_contact_impedance : s.contact_impedance;
  x << "<mujoco model=\"peer\">\n<option timestep=\"" << (soft ? s.flex_timestep : s.timestep)
    << "\" gravity=\"0 0 0\"" << (soft ? " integrator=\"discrete\"" : "")
    << "><flag multiccd=\"enable\"" << (soft && s.ipc ? " ipc=\"enable\"" : "")
    << "/></option>\n<default><geom solref=\"" << time_constant << " 1\" solimp=\"" << impedance
    << ' ' << impedance << " 0.001\"/></default>\n<asset>";
  write_mesh_asset(x, "object", object);
  x << "</asset>\n<worldbody>\n<body name=\"object\"><freejoint name=\"object\"/>"
       "<geom name=\"object\" type=\"mesh\" mesh=\"object\" density=\""
    << density << "\" friction=\"" << friction << " 0.005 0.0001\""
    << (soft ? " contype=\"2\" conaffinity=\"1\"" : "") << "/></body>\n";
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
      << p.grip_force / p.squeeze_speed << "\"/>";
    if (soft) {
      x << "<inertial pos=\"0 0 0\" mass=\"" << s.jaw_mass << "\" diaginertia=\"1e-5 1e-5 1e-5\"/>";
    } else {
      write_box_finger(x, j, gripper, friction, s);
    }
    x << "</body>\n";
    if (soft) write_flex_finger(x, j, *gripper.soft_finger, finger, friction, s);
  }
  x << "</worldbody>\n<contact><exclude body1=\"jaw0\" body2=\"jaw1\"/></contact>\n";
  if (soft) write_flex_mounts(x, s);
  x << "<actuator>";
  for (int j = 0; j < 2; ++j) x << "<motor name=\"jaw" << j << "\" joint=\"jaw" << j << "\"/>";
  x << "</actuator>\n</mujoco>\n";
  return x.str();
}

// One trial's simulation over a compiled model.
class Simulation {
 public:
  Simulation(mjModel* m, mjData* d, const grippers::ParallelGripper& gripper,
             const trial::TrialParameters& p, const MujocoSettings& s)
      : m_(m), d_(d), gripper_(gripper), p_(p), s_(s) {
    object_body_ = mj_name2id(m, mjOBJ_BODY, "object");
    object_geom_ = mj_name2id(m, mjOBJ_GEOM, "object");
    const int joint = m->body_jntadr[object_body_];
    object_qpos_ = m->jnt_qposadr[joint];
    object_dof_ = m->jnt_dofadr[joint];
    for (int j = 0; j < 2; ++j) {
      const std::string name = "jaw" + std::to_string(j);
      jaw_body_[j] = mj_name2id(m, mjOBJ_BODY, name.c_str());
      jaw_geom_[j] = mj_name2id(m, mjOBJ_GEOM, name.c_str());  // -1: a soft finger
      finger_flex_[j] = mj_name2id(m, mjOBJ_FLEX, ("finger" + std::to_string(j)).c_str());
      const int jaw_joint = mj_name2id(m, mjOBJ_JOINT, name.c_str());
      jaw_qpos_[j] = m->jnt_qposadr[jaw_joint];
      jaw_joint_[j] = jaw_joint;
      travel_[j] = m->jnt_range[2 * jaw_joint + 1];
      d->ctrl[mj_name2id(m, mjOBJ_ACTUATOR, name.c_str())] = p.grip_force;
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
    const double closing_time = std::max(travel_[0], travel_[1]) / p_.squeeze_speed +
                                (gripper_.soft_finger ? s_.flex_closing_margin : s_.closing_margin);
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
    for (int j = 0; j < 2; ++j) {
      out.fingers[j] = body_pose(d_, jaw_body_[j]);
      if (finger_flex_[j] >= 0) out.finger_vertices[j] = flex_vertices(finger_flex_[j]);
    }
    if (gripper_.soft_finger) record_patch();
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
      slip[phase] = gripper_.soft_finger
                        ? (object_center() - patch_.motion(flex_positions())(center)).norm()
                        : (object_center() - center - jaw_motion(weight, out)).norm();
      seconds[phase] = static_cast<double>(phase_windows) * p_.sim.dt;
      out.largest_slip = std::max(out.largest_slip, slip[phase]);
    }
    out.verdict = !touching_                                           ? "lost_contact"
                  : trial::slipped_beyond_threshold(p_, slip, seconds) ? "displaced"
                                                                       : "success";
    return out;
  }

  // The state where the trial ended, into `out`'s final_* fields.
  void record_end(MujocoOutcome& out) const {
    out.final_object = body_pose(d_, object_body_);
    for (int j = 0; j < 2; ++j) {
      out.final_fingers[j] = body_pose(d_, jaw_body_[j]);
      if (finger_flex_[j] >= 0) out.final_finger_vertices[j] = flex_vertices(finger_flex_[j]);
    }
  }

  // Over every step so far: MuJoCo's deepest contact between object and a finger (m), and the
  // most of a soft finger's tets inverted at once.
  double deepest_penetration() const { return deepest_penetration_; }
  int most_inverted_tets() const { return most_inverted_tets_; }

 private:
  // One grip step (p.sim.dt) of MuJoCo steps; mean_force_ and jaw_speed_ are each jaw's mean
  // force and speed over it,
  // touching_ whether the object touched a jaw at its last step. MuJoCo's contacts chatter from
  // step to step (contact points come and go); grip's step is what the protocol's rates and
  // forces are measured over.
  bool window(const Eigen::Vector3d& g, bool hold) {
    const double h = m_->opt.timestep;
    const long n = std::max(1L, std::lround(p_.sim.dt / h));
    const std::array<double, 2> start = {d_->qpos[jaw_qpos_[0]], d_->qpos[jaw_qpos_[1]]};
    mean_force_ = {0.0, 0.0};
    for (long k = 0; k < n; ++k) {
      if (!step(g, hold)) return false;
      touching_ = false;
      for (int j = 0; j < 2; ++j) mean_force_[j] += jaw_force(j) / static_cast<double>(n);
    }
    for (int j = 0; j < 2; ++j) {
      jaw_speed_[j] = std::abs(d_->qpos[jaw_qpos_[j]] - start[j]) / (static_cast<double>(n) * h);
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
    watch_invariants();
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
      const int side = finger_side(contact, j);
      if (side < 0) continue;
      const bool jaw_second = side == 1;
      mjtNum f[6];
      mj_contactForce(m_, d_, c, f);  // in the contact frame: normal, two tangents
      const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> frame(contact.frame);
      const Eigen::Vector3d on_second = frame.transpose() * Eigen::Vector3d(f[0], f[1], f[2]);
      sum -= (jaw_second ? on_second : -on_second).dot(closing);
      touching_ = touching_ || f[0] > 0.0;
    }
    return sum;
  }

  // Which side of `contact` (0 or 1) is jaw j's finger when the other is the object; -1 if the
  // contact is not between them.
  int finger_side(const mjContact& contact, int j) const {
    for (int side = 0; side < 2; ++side) {
      const bool finger = finger_flex_[j] >= 0 ? contact.flex[side] == finger_flex_[j]
                                               : contact.geom[side] == jaw_geom_[j];
      if (finger && contact.geom[1 - side] == object_geom_) return side;
    }
    return -1;
  }

  // The rigid jaws' contact patch moves with them: their displacements since the settled grasp,
  // weighted by their forces.
  Eigen::Vector3d jaw_motion(const std::array<double, 2>& weight, const MujocoOutcome& out) const {
    Eigen::Vector3d patch = Eigen::Vector3d::Zero();
    for (int j = 0; j < 2; ++j) {
      patch +=
          weight[j] * (body_pose(d_, jaw_body_[j]).translation() - out.fingers[j].translation());
    }
    return patch;
  }

  // A flex's vertices in the world, in the finger mesh's vertex order.
  FlexVertices flex_vertices(int flex) const {
    const int first = m_->flex_vertadr[flex], count = m_->flex_vertnum[flex];
    return FlexVertices(d_->flexvert_xpos + 3 * first, count, 3);
  }
  // Every flex vertex in the world (both fingers, in model order): the rows patch_ indexes.
  FlexVertices flex_positions() const { return FlexVertices(d_->flexvert_xpos, m_->nflexvert, 3); }

  // The soft fingers' settled contact patch, as grip's trial records its own: the flex vertices
  // that bear the object's contacts, weighted by their normal force (a contact on a tet's face
  // or edge shares its force among the element's vertices).
  void record_patch() {
    const FlexVertices x = flex_positions();
    for (int c = 0; c < d_->ncon; ++c) {
      const mjContact& contact = d_->contact[c];
      for (int j = 0; j < 2; ++j) {
        const int side = finger_side(contact, j);
        if (side < 0) continue;
        mjtNum f[6];
        mj_contactForce(m_, d_, c, f);
        if (!(f[0] > 0.0)) continue;
        const int flex = finger_flex_[j];
        std::vector<int> vertices;
        if (contact.vert[side] >= 0) {
          vertices.push_back(contact.vert[side]);
        } else if (contact.elem[side] >= 0) {
          const int* elem = m_->flex_elem + m_->flex_elemdataadr[flex] +
                            (m_->flex_dim[flex] + 1) * contact.elem[side];
          vertices.assign(elem, elem + m_->flex_dim[flex] + 1);
        }
        for (const int v : vertices) {
          const int row = m_->flex_vertadr[flex] + v;
          patch_.add(row, x.row(row).transpose(), f[0] / static_cast<double>(vertices.size()));
        }
      }
    }
  }

  // Records the deepest object-finger contact and, for soft fingers, their inverted tets.
  void watch_invariants() {
    for (int c = 0; c < d_->ncon; ++c) {
      const mjContact& contact = d_->contact[c];
      if (finger_side(contact, 0) >= 0 || finger_side(contact, 1) >= 0) {
        deepest_penetration_ = std::max(deepest_penetration_, -contact.dist);
      }
    }
    if (!gripper_.soft_finger) return;
    int inverted = 0;
    for (int j = 0; j < 2; ++j) {
      inverted += inverted_tets(gripper_.soft_finger->mesh, flex_vertices(finger_flex_[j]));
    }
    most_inverted_tets_ = std::max(most_inverted_tets_, inverted);
  }

  MujocoOutcome& unstable(MujocoOutcome& out) const {
    out.verdict = "numerical";
    out.message = "MuJoCo: unstable simulation (bad qacc), state reset";
    return out;
  }

  mjModel* m_;  // its gravity changes per phase
  mjData* d_;
  const grippers::ParallelGripper& gripper_;
  const trial::TrialParameters& p_;
  const MujocoSettings& s_;
  int object_body_ = -1, object_geom_ = -1, object_qpos_ = -1, object_dof_ = -1;
  std::array<int, 2> jaw_body_{}, jaw_geom_{}, jaw_qpos_{};
  std::array<double, 2> travel_{};
  std::array<int, 2> jaw_joint_{};
  std::array<int, 2> finger_flex_{};  // -1: a rigid jaw
  trial::ContactPatch patch_;         // soft fingers': rows of flex_positions()
  double deepest_penetration_ = 0.0;
  int most_inverted_tets_ = 0;
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
  Simulation simulation(m, d, gripper, parameters, settings);
  MujocoOutcome out = simulation.run();
  simulation.record_end(out);
  if (!out.settled) {
    out.object = out.final_object;
    out.fingers = out.final_fingers;
    out.finger_vertices = out.final_finger_vertices;
  }
  out.deepest_penetration = simulation.deepest_penetration();
  out.most_inverted_tets = simulation.most_inverted_tets();
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
