#include "src/synth/hand_optimizer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "src/geometry/surface_sampling.hpp"
#include "src/synth/candidate_random.hpp"
#include "src/synth/convex_hull.hpp"

namespace grip::synth {
namespace {

constexpr std::uint32_t kPenetrationStream = 22;
constexpr std::uint32_t kAttemptStream = 23;

// A rotation whose z axis is `z` (unit), turned by `spin` about it.
Eigen::Matrix3d frame_with_z(const Eigen::Vector3d& z, double spin) {
  const Eigen::Vector3d helper =
      std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d x0 = z.cross(helper).normalized();
  const Eigen::Vector3d x = Eigen::AngleAxisd(spin, z) * x0;
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = z.cross(x);
  r.col(2) = z;
  return r;
}

HandState initial_state(const PreparedHand& hand, const ConvexHull& hull,
                        const HandOptimizerParams& params, CandidateRandom& random) {
  const grippers::KinematicTree& tree = hand.kinematics();
  // A direction uniform on the sphere; the hull point it leaves through, and that facet's normal.
  const Eigen::Vector3d direction(random.normal(), random.normal(), random.normal());
  const ConvexHull::Exit on_hull = hull.exit(direction);
  const Eigen::Vector3d& p = on_hull.point;
  const Eigen::Vector3d& n = on_hull.normal;
  // The palm faces the hull (+z of the palm along -n), tilted within the jitter cone.
  const Eigen::Vector3d tilt_axis =
      frame_with_z(n, random.uniform(0.0, 2.0 * std::numbers::pi)).col(0);
  const Eigen::Vector3d z =
      Eigen::AngleAxisd(random.uniform(0.0, params.approach_jitter), tilt_axis) * (-n);
  HandState state;
  state.base.linear() = frame_with_z(z, random.uniform(0.0, 2.0 * std::numbers::pi));
  const double distance = random.uniform(params.hull_distance_min, params.hull_distance_max);
  state.base.translation() = p + n * distance - state.base.linear() * kPalmGraspPoint;

  // Joints: a quarter of the way from 0 to the upper limit, spread fingers centred on 0.
  const Eigen::VectorXd& lower = tree.lower_limits();
  const Eigen::VectorXd& upper = tree.upper_limits();
  state.joints.resize(tree.dof_count());
  for (int d = 0; d < tree.dof_count(); ++d) {
    const std::string& name = tree.dof_joint(d).name;
    const bool finger_abduction = name.ends_with("_abd") && !name.starts_with("thumb");
    const double zero = std::clamp(0.0, lower(d), upper(d));
    const double mean = finger_abduction ? zero : zero + 0.25 * (upper(d) - zero);
    state.joints(d) = mean + params.joint_jitter * random.normal();
  }
  state.joints = tree.clamp_to_limits(state.joints);
  state.contacts.resize(static_cast<std::size_t>(params.contacts));
  for (int& c : state.contacts) c = random.below(static_cast<int>(hand.contacts().size()));
  return state;
}

}  // namespace

SynthesisResult optimize_hand_grasps(const PreparedObject& object, const PreparedHand& hand,
                                     const HandOptimizerParams& params, std::uint64_t seed,
                                     int count) {
  const grippers::KinematicTree& tree = hand.kinematics();
  const ConvexHull hull(object.surface().vertices);
  const geometry::SurfaceSamples penetration =
      geometry::sample_surface(object.surface(), params.penetration_points,
                               CandidateRandom(seed, kPenetrationStream, 0).below(1 << 30));
  const HandEnergy energy(hand, object, penetration.points, params.weights);
  const int dofs = tree.dof_count();

  const auto attempt = [&](std::int64_t index) -> AttemptOutcome {
    CandidateRandom random(seed, kAttemptStream, static_cast<std::uint64_t>(index));
    HandState state = initial_state(hand, hull, params, random);
    Eigen::VectorXd gradient;
    HandEnergyTerms terms = energy.evaluate(state, &gradient);
    Eigen::VectorXd mean_square = Eigen::VectorXd::Zero(6 + dofs);
    const int period = std::max(1, params.steps / params.annealing_periods);
    for (int step = 0; step < params.steps; ++step) {
      const double decay = std::pow(params.temperature_decay, step / period);
      mean_square = params.rms_decay * mean_square +
                    (1.0 - params.rms_decay) * gradient.cwiseProduct(gradient);
      const Eigen::VectorXd move =
          -params.step_size * decay *
          gradient.cwiseQuotient((mean_square.cwiseSqrt().array() + 1e-6).matrix());
      HandState proposal = HandEnergy::moved(state, move);
      proposal.joints = tree.clamp_to_limits(proposal.joints);
      for (int& c : proposal.contacts) {
        if (random.uniform() < params.switch_probability) {
          c = random.below(static_cast<int>(hand.contacts().size()));
        }
      }
      Eigen::VectorXd proposal_gradient;
      const HandEnergyTerms proposal_terms = energy.evaluate(proposal, &proposal_gradient);
      const double temperature = params.starting_temperature * decay;
      const double u = random.uniform();
      if (proposal_terms.total < terms.total ||
          u < std::exp((terms.total - proposal_terms.total) / temperature)) {
        state = std::move(proposal);
        terms = proposal_terms;
        gradient = std::move(proposal_gradient);
      }
    }

    const std::optional<FixedHand> fixed =
        fix_hand_clearance(hand, object, state, params.clearance);
    if (!fixed) return {std::nullopt, "penetration left after the clearance fix"};
    const std::vector<Eigen::Isometry3d> poses =
        tree.link_poses(fixed->state.base, fixed->state.joints);
    if (hand.self_intersections(poses) > 0) return {std::nullopt, "hand intersects itself"};
    const HandEnergyTerms fixed_terms = energy.evaluate(fixed->state, nullptr);
    if (fixed_terms.fc > params.max_force_closure_error) {
      return {std::nullopt, "not a force closure"};
    }

    HandGrasp grasp;
    grasp.pose = fixed->state.base;
    grasp.joints = fixed->state.joints;
    const auto n_c = static_cast<int>(fixed->state.contacts.size());
    grasp.contacts.resize(n_c, 3);
    grasp.contact_normals.resize(n_c, 3);
    for (int i = 0; i < n_c; ++i) {
      const PreparedHand::LinkPoint& c = hand.contacts()[static_cast<std::size_t>(
          fixed->state.contacts[static_cast<std::size_t>(i)])];
      const Eigen::Vector3d x = poses[static_cast<std::size_t>(c.link)] * c.position;
      grasp.contacts.row(i) = x.transpose();
      grasp.contact_normals.row(i) =
          object.tree().face_normal(object.tree().closest(x).face).transpose();
    }
    Candidate candidate;
    candidate.gripper = grippers::GripperKind::kLeap;
    candidate.hands.push_back(std::move(grasp));
    candidate.energies = {{"fc", fixed_terms.fc},         {"dis", fixed_terms.dis},
                          {"pen", fixed_terms.pen},       {"spen", fixed_terms.spen},
                          {"joints", fixed_terms.joints}, {"normal", fixed_terms.normal},
                          {"total", fixed_terms.total}};
    candidate.min_distance = fixed->min_distance;
    return {std::move(candidate), ""};
  };
  return run_attempts(count, params.max_attempts_per_candidate * std::max(count, 1), params.block,
                      attempt);
}

}  // namespace grip::synth
