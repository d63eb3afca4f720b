#include "solver/newton/step_targets.hpp"

#include "solver/body/kinematic_motion.hpp"

namespace grip::solver {
namespace {

// Body b's collision vertices: rows [first, first + vertices.size()) of a collision array.
struct CollisionRange {
  Eigen::Index first;
  std::span<const int> vertices;  // their indices among the body's vertices
};

CollisionRange collision_range(const CollisionMesh& mesh, int b) {
  const int first = mesh.body_first_vertex[b], end = mesh.body_first_vertex[b + 1];
  return {first, {mesh.vertex_local.data() + first, static_cast<std::size_t>(end - first)}};
}

// The collision vertices of bodies without DOFs at the poses `start` and `target` (zero rows
// elsewhere).
void kinematic_vertices(const Model& model, const State& state, const std::vector<Pose>& start,
                        const std::vector<Pose>& target, StepTargets& targets) {
  const CollisionMesh& mesh = model.collision();
  targets.kinematic_start.setZero(mesh.size(), 3);
  targets.kinematic_target.setZero(mesh.size(), 3);
  for (int b = 0; b < static_cast<int>(model.bodies().size()); ++b) {
    const BodyModel& body = model.bodies()[b];
    if (body.has_dofs()) continue;
    const CollisionRange range = collision_range(mesh, b);
    body.kind->vertex_positions(body.local, state.q, start[b], range.vertices,
                                targets.kinematic_start, range.first);
    body.kind->vertex_positions(body.local, state.q, target[b], range.vertices,
                                targets.kinematic_target, range.first);
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
        model.bodies()[b].scripted()
            ? kinematic::advance(state.scripts[b], state.poses[b], state.time + h, h)
            : state.poses[b];
  }
  kinematic_vertices(model, state, state.poses, targets.pose_target, targets);
  targets.prescribed_target = state.q;
  for (const PinnedVertex& pin : model.pins()) {
    const BodyModel& body = model.bodies()[pin.body];
    const int o = body.kind->vertex_block(body.local, pin.vertex);
    targets.prescribed_target.segment<3>(o) =
        kinematic::apply(targets.pose_target[pin.kinematic_body], pin.offset);
  }
  return targets;
}

StepTargets targets_at_rest(const Model& model, const State& state) {
  StepTargets now;
  kinematic_vertices(model, state, state.poses, state.poses, now);
  return now;
}

Vertices collision_positions(const Model& model, const Eigen::VectorXd& q,
                             const StepTargets& targets, double progress) {
  const CollisionMesh& mesh = model.collision();
  Vertices x(mesh.size(), 3);
  for (int b = 0; b < static_cast<int>(model.bodies().size()); ++b) {
    const BodyModel& body = model.bodies()[b];
    const CollisionRange range = collision_range(mesh, b);
    if (body.has_dofs()) {
      body.kind->vertex_positions(body.local, q, Pose{}, range.vertices, x, range.first);
      continue;
    }
    for (Eigen::Index i = range.first;
         i < range.first + static_cast<Eigen::Index>(range.vertices.size()); ++i) {
      x.row(i) = (1.0 - progress) * targets.kinematic_start.row(i) +
                 progress * targets.kinematic_target.row(i);
    }
  }
  return x;
}

}  // namespace grip::solver
