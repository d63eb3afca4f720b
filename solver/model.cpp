#include "solver/model.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "solver/kernels/affine_body.hpp"
#include "solver/linear/block_ordering.hpp"

namespace grip::solver {
namespace {

[[noreturn]] void invalid(const BodyDescription& body, const std::string& problem) {
  throw std::invalid_argument("body '" + body.name + "': " + problem);
}

// Mass, first and second moments of a closed surface of unit density, by the divergence
// theorem: the signed tetrahedra from the origin to each outward triangle.
struct VolumeMoments {
  double volume = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();   // integral of x
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // integral of x x^T
};

VolumeMoments volume_moments(const Vertices& v, const Triangles& f) {
  VolumeMoments m;
  for (Eigen::Index t = 0; t < f.rows(); ++t) {
    const Eigen::Vector3d a = v.row(f(t, 0)), b = v.row(f(t, 1)), c = v.row(f(t, 2));
    const double vol = a.dot(b.cross(c)) / 6.0;
    const Eigen::Vector3d s = a + b + c;
    m.volume += vol;
    m.first += vol * s / 4.0;
    m.second += vol / 20.0 *
                (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  return m;
}

// M = integral of rho J^T J over the body, J(x) = J0 + sum_k x_k J_k linear in the rest point,
// written through the kernel's Jacobian so it holds for its DOF layout.
Matrix12d affine_mass_matrix(double density, const VolumeMoments& m) {
  using Jacobian = Eigen::Matrix<double, 3, 12>;
  const Jacobian j0 = kernels::affine_body_jacobian(Eigen::Vector3d::Zero());
  Jacobian jk[3];
  for (int k = 0; k < 3; ++k) jk[k] = kernels::affine_body_jacobian(Eigen::Vector3d::Unit(k)) - j0;
  Matrix12d mass = m.volume * j0.transpose() * j0;
  for (int k = 0; k < 3; ++k) {
    mass += m.first[k] * (j0.transpose() * jk[k] + jk[k].transpose() * j0);
    for (int l = 0; l < 3; ++l) mass += m.second(k, l) * jk[k].transpose() * jk[l];
  }
  return density * mass;
}

void check_surface(const BodyDescription& body) {
  if (body.vertices.rows() == 0 || body.triangles.rows() == 0) invalid(body, "has no surface");
  if (!body.vertices.allFinite()) invalid(body, "has non-finite vertex coordinates");
  if (body.triangles.minCoeff() < 0 || body.triangles.maxCoeff() >= body.vertices.rows()) {
    invalid(body, "has a triangle index outside its vertices");
  }
}

// Blocks of the Newton matrix: one per FEM vertex (3 DOFs) and per affine body (12), coupled
// by the tets; a pinned vertex is solved for by an identity row, so it couples to nothing.
BlockGraph block_graph(const Model& model) {
  BlockGraph graph;
  std::vector<int> first_block;  // per body
  for (const BodyModel& body : model.bodies()) {
    first_block.push_back(static_cast<int>(graph.block_offset.size()));
    const int size = body.type == BodyType::kFem ? 3 : 12;
    for (int d = 0; d < body.dof_count; d += size)
      graph.block_offset.push_back(body.dof_offset + d);
  }
  graph.block_offset.push_back(model.dof_count());
  graph.neighbours.resize(graph.block_offset.size() - 1);
  const std::vector<char>& prescribed = model.prescribed();
  for (std::size_t b = 0; b < model.bodies().size(); ++b) {
    const BodyModel& body = model.bodies()[b];
    auto free = [&](int v) { return !prescribed[body.dof_offset + 3 * v]; };
    for (const FemTet& tet : body.tets) {
      for (int i : tet.vertices) {
        for (int j : tet.vertices) {
          if (i != j && free(i) && free(j))
            graph.neighbours[first_block[b] + i].push_back(first_block[b] + j);
        }
      }
    }
  }
  return graph;
}

}  // namespace

std::shared_ptr<const Model> Model::build(const SceneDescription& scene) {
  auto model = std::make_shared<Model>();
  model->scene_ = scene;
  model->sim_ = scene.sim;
  const int body_count = static_cast<int>(scene.bodies.size());
  int dofs = 0;

  for (const BodyDescription& body : scene.bodies) {
    check_surface(body);
    BodyModel b;
    b.name = body.name;
    b.type = body.type;
    b.material = body.material;
    b.dof_offset = dofs;
    const Eigen::Matrix3d r = body.pose.rotation.normalized().toRotationMatrix();

    if (body.type == BodyType::kFem) {
      if (body.tets.rows() == 0) invalid(body, "is FEM but has no tetrahedra");
      if (body.tets.minCoeff() < 0 || body.tets.maxCoeff() >= body.vertices.rows()) {
        invalid(body, "has a tetrahedron index outside its vertices");
      }
      if (body.material.density <= 0 || body.material.youngs <= 0 || body.material.poisson <= -1 ||
          body.material.poisson >= 0.5) {
        invalid(body, "needs density > 0, youngs > 0 and -1 < poisson < 0.5");
      }
      b.rest = (body.vertices * r.transpose()).rowwise() + body.pose.position.transpose();
      b.vertex_mass = Eigen::VectorXd::Zero(b.rest.rows());
      b.elasticity =
          kernels::stable_neo_hookean_parameters(body.material.youngs, body.material.poisson);
      for (Eigen::Index t = 0; t < body.tets.rows(); ++t) {
        FemTet tet;
        for (int i = 0; i < 4; ++i) tet.vertices[i] = body.tets(t, i);
        const Eigen::Vector3d x0 = b.rest.row(tet.vertices[0]), x1 = b.rest.row(tet.vertices[1]),
                              x2 = b.rest.row(tet.vertices[2]), x3 = b.rest.row(tet.vertices[3]);
        tet.rest_volume = kernels::tet_rest_volume(x0, x1, x2, x3);
        if (!(tet.rest_volume > 0)) {
          invalid(body, "tetrahedron " + std::to_string(t) +
                            " is inverted or flat at rest (volume " +
                            std::to_string(tet.rest_volume) + " m^3)");
        }
        tet.rest_shape_inverse = kernels::tet_rest_shape_inverse(x0, x1, x2, x3);
        for (int i = 0; i < 4; ++i) {
          b.vertex_mass[tet.vertices[i]] += body.material.density * tet.rest_volume / 4.0;
        }
        b.tets.push_back(tet);
      }
      if ((b.vertex_mass.array() <= 0).any()) {
        invalid(body, "has a vertex that belongs to no tetrahedron");
      }
      b.dof_count = 3 * static_cast<int>(b.rest.rows());
    } else if (body.type == BodyType::kAffine) {
      if (body.material.density <= 0) invalid(body, "needs density > 0");
      if (body.orthogonality_stiffness <= 0) invalid(body, "needs orthogonality_stiffness > 0");
      const VolumeMoments raw = volume_moments(body.vertices, body.triangles);
      if (!(raw.volume > 0)) {
        invalid(body, "encloses no positive volume (is its surface closed and outward?)");
      }
      b.center_of_mass_offset = raw.first / raw.volume;
      b.rest = body.vertices.rowwise() - b.center_of_mass_offset.transpose();
      const VolumeMoments centred = volume_moments(b.rest, body.triangles);
      b.volume = centred.volume;
      b.mass_matrix = affine_mass_matrix(body.material.density, centred);
      b.mass_matrix_inverse = b.mass_matrix.inverse();
      b.orthogonality_stiffness = body.orthogonality_stiffness;
      b.dof_count = 12;
    } else {
      b.rest = body.vertices;
      b.dof_count = 0;
    }
    dofs += b.dof_count;
    model->bodies_.push_back(std::move(b));
  }
  model->dof_count_ = dofs;

  // Which pairs may touch, and with what friction.
  model->pair_friction_.assign(static_cast<std::size_t>(body_count) * body_count, -1.0);
  for (int a = 0; a < body_count; ++a) {
    for (int b = 0; b < body_count; ++b) {
      const BodyType ta = scene.bodies[a].type, tb = scene.bodies[b].type;
      if (ta == BodyType::kKinematic && tb == BodyType::kKinematic) continue;
      if (a == b && ta != BodyType::kFem) continue;
      model->pair_friction_[a * body_count + b] =
          std::sqrt(scene.bodies[a].material.friction * scene.bodies[b].material.friction);
    }
  }
  for (const ContactOverride& c : scene.contacts) {
    if (c.body_a < 0 || c.body_a >= body_count || c.body_b < 0 || c.body_b >= body_count) {
      throw std::invalid_argument("contact override names a body that does not exist");
    }
    if (c.friction < 0) throw std::invalid_argument("contact friction must be >= 0");
    for (const auto& [a, b] : {std::pair{c.body_a, c.body_b}, std::pair{c.body_b, c.body_a}}) {
      if (model->pair_friction_[a * body_count + b] >= 0) {
        model->pair_friction_[a * body_count + b] = c.friction;
      }
    }
  }

  // Pins: prescribed DOFs, and no contact between a pinned body and its mount.
  model->prescribed_.assign(dofs, 0);
  for (int index = 0; index < body_count; ++index) {
    const BodyDescription& body = scene.bodies[index];
    if (!body.pins.empty() && body.type != BodyType::kFem)
      invalid(body, "only FEM bodies have pins");
    for (const Pin& pin : body.pins) {
      if (pin.kinematic_body < 0 || pin.kinematic_body >= body_count ||
          scene.bodies[pin.kinematic_body].type != BodyType::kKinematic) {
        invalid(body, "is pinned to something that is not a kinematic body");
      }
      const BodyDescription& mount = scene.bodies[pin.kinematic_body];
      const Eigen::Matrix3d mount_r = mount.pose.rotation.normalized().toRotationMatrix();
      for (int v : pin.vertices) {
        if (v < 0 || v >= body.vertices.rows()) invalid(body, "pins a vertex it does not have");
        const BodyModel& b = model->bodies_[index];
        const Eigen::Vector3d world = b.rest.row(v);
        model->pins_.push_back(
            {index, v, pin.kinematic_body, mount_r.transpose() * (world - mount.pose.position)});
        for (int k = 0; k < 3; ++k) model->prescribed_[b.dof_offset + 3 * v + k] = 1;
      }
      model->pair_friction_[index * body_count + pin.kinematic_body] = -1.0;
      model->pair_friction_[pin.kinematic_body * body_count + index] = -1.0;
    }
  }

  model->ordering_ =
      std::make_shared<const std::vector<int>>(nested_dissection_ordering(block_graph(*model)));

  // The collision mesh: every surface vertex, edge and face of every body.
  CollisionMesh& mesh = model->collision_;
  for (int index = 0; index < body_count; ++index) {
    const BodyDescription& body = scene.bodies[index];
    std::map<int, int> to_collision;
    auto collision_vertex = [&](int local) {
      auto [it, added] = to_collision.try_emplace(local, mesh.size());
      if (added) {
        mesh.vertex_body.push_back(index);
        mesh.vertex_local.push_back(local);
      }
      return it->second;
    };
    std::map<std::pair<int, int>, int> edge_seen;
    for (Eigen::Index t = 0; t < body.triangles.rows(); ++t) {
      std::array<int, 3> face;
      for (int i = 0; i < 3; ++i) face[i] = collision_vertex(body.triangles(t, i));
      mesh.faces.push_back(face);
      for (int i = 0; i < 3; ++i) {
        const int a = std::min(face[i], face[(i + 1) % 3]),
                  b = std::max(face[i], face[(i + 1) % 3]);
        if (edge_seen.emplace(std::pair{a, b}, 0).second) mesh.edges.push_back({a, b});
      }
    }
  }
  return model;
}

}  // namespace grip::solver
