#include "solver/batch/model_batch.hpp"

#include "solver/body/driven_bodies.hpp"

namespace grip::solver::parallel {

FemBatch fem_batch(const std::vector<const Model*>& environments) {
  FemBatch batch;
  for (const Model* model : environments) {
    batch.begin_environment(model->dof_count());
    for (const BodyModel& body : model->bodies()) {
      if (!body.deforms()) continue;
      std::vector<double> rest;
      for (int v = 0; v < body.kind->vertex_count(body.local); ++v) {
        const Eigen::Vector3d x = body.kind->rest_vertex(body.local, v);
        rest.insert(rest.end(), {x.x(), x.y(), x.z()});
      }
      std::vector<int> tets;
      for (const std::array<int, 4>& tet : body.kind->tets(body.local)) {
        tets.insert(tets.end(), tet.begin(), tet.end());
      }
      const Material& m = body.material;
      batch.add_body(body.dof_offset, rest, tets, {m.youngs, m.poisson, m.density, m.damping});
    }
  }
  batch.finish();
  return batch;
}

AffineBatch affine_batch(const std::vector<const Model*>& environments) {
  AffineBatch batch;
  for (const Model* model : environments) {
    batch.begin_environment(model->dof_count());
    for (const BodyModel& body : model->bodies()) {
      const auto* affine = dynamic_cast<const AffineBodies*>(body.kind);
      if (!affine) continue;
      const auto* driven = dynamic_cast<const DrivenBodies*>(body.kind);
      const int i = body.local;
      batch.add_body(body.dof_offset,
                     {affine->mass_matrix(i).data(), affine->mass_matrix_inverse(i).data(),
                      affine->density(i), affine->volume(i), affine->orthogonality_stiffness(i),
                      driven == nullptr, driven ? driven->drive_stiffness(i) : 0.0});
    }
  }
  return batch;
}

CollisionBatch collision_batch(const std::vector<const Model*>& environments) {
  CollisionBatch batch;
  for (const Model* model : environments) {
    batch.begin_environment(model->dof_count());
    const CollisionMesh& mesh = model->collision();
    for (int v = 0; v < mesh.size(); ++v) {
      const BodyModel& body = model->bodies()[static_cast<std::size_t>(mesh.vertex_body[v])];
      const int local = mesh.vertex_local[v];
      if (!body.has_dofs()) {
        batch.add_scripted_vertex();
      } else if (body.deforms()) {
        batch.add_fem_vertex(body.kind->vertex_block(body.local, local));
      } else {
        const Eigen::Vector3d rest = body.kind->rest_vertex(body.local, local);
        batch.add_affine_vertex(body.kind->vertex_block(body.local, local), rest.x(), rest.y(),
                                rest.z());
      }
    }
  }
  return batch;
}

std::vector<char> prescribed_dofs(const std::vector<const Model*>& environments) {
  std::vector<char> prescribed;
  for (const Model* model : environments) {
    prescribed.insert(prescribed.end(), model->prescribed().begin(), model->prescribed().end());
  }
  return prescribed;
}

SurfaceBatch surface_batch(const std::vector<const Model*>& environments) {
  SurfaceBatch batch;
  for (const Model* model : environments) {
    const CollisionMesh& mesh = model->collision();
    batch.begin_environment(mesh.friction, mesh.untouching);
    for (int v = 0; v < mesh.size(); ++v) {
      batch.add_vertex(mesh.vertex_body[v], mesh.rest(v, 0), mesh.rest(v, 1), mesh.rest(v, 2));
    }
    for (const auto& e : mesh.edges) batch.add_edge(e[0], e[1]);
    for (const auto& f : mesh.faces) batch.add_face(f[0], f[1], f[2]);
    batch.set_near_at_rest(mesh.point_triangle_near_at_rest, mesh.edge_edge_near_at_rest);
  }
  return batch;
}

}  // namespace grip::solver::parallel
