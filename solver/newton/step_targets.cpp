#include "solver/newton/step_targets.hpp"

#include "solver/body/body.hpp"
#include "solver/body/kinematic_body.hpp"

namespace grip::solver {
namespace {

// Kinematic collision vertices at the poses `start` and `target` (zero rows elsewhere).
void kinematic_vertices(const Model& model, const std::vector<Pose>& start,
                        const std::vector<Pose>& target, StepTargets& targets) {
  const CollisionMesh& mesh = model.collision();
  targets.kinematic_start.setZero(mesh.size(), 3);
  targets.kinematic_target.setZero(mesh.size(), 3);
  for (int i = 0; i < mesh.size(); ++i) {
    const int b = mesh.vertex_body[i];
    if (!is_kinematic(model.bodies()[b])) continue;
    const Eigen::Vector3d rest = model.bodies()[b].rest.row(mesh.vertex_local[i]);
    targets.kinematic_start.row(i) = kinematic::apply(start[b], rest);
    targets.kinematic_target.row(i) = kinematic::apply(target[b], rest);
  }
}

}  // namespace

StepTargets step_targets(const Model& model, const State& state, double h) {
  const int body_count = static_cast<int>(model.bodies().size());
  StepTargets targets;
  targets.q_start = state.q;
  targets.pose_target.resize(body_count);
  for (int b = 0; b < body_count; ++b) {
    targets.pose_target[b] =
        is_scripted(model.bodies()[b])
            ? kinematic::advance(state.scripts[b], state.poses[b], state.time + h, h)
            : state.poses[b];
  }
  kinematic_vertices(model, state.poses, targets.pose_target, targets);
  targets.prescribed_target = state.q;
  for (const PinnedVertex& pin : model.pins()) {
    const int o = model.bodies()[pin.body].dof_offset + 3 * pin.vertex;
    targets.prescribed_target.segment<3>(o) =
        kinematic::apply(targets.pose_target[pin.kinematic_body], pin.offset);
  }
  return targets;
}

StepTargets targets_at_rest(const Model& model, const State& state) {
  StepTargets now;
  kinematic_vertices(model, state.poses, state.poses, now);
  return now;
}

Vertices collision_positions(const Model& model, const Eigen::VectorXd& q,
                             const StepTargets& targets, double progress) {
  const CollisionMesh& mesh = model.collision();
  Vertices x(mesh.size(), 3);
  for (int i = 0; i < mesh.size(); ++i) {
    const BodyModel& body = model.bodies()[mesh.vertex_body[i]];
    if (is_kinematic(body)) {
      x.row(i) = (1.0 - progress) * targets.kinematic_start.row(i) +
                 progress * targets.kinematic_target.row(i);
    } else {
      x.row(i) = vertex_position(body, q, Pose{}, mesh.vertex_local[i]);
    }
  }
  return x;
}

}  // namespace grip::solver
