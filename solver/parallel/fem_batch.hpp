#pragma once
// The FEM tets of a whole batch of environments in flat arrays, as the data-parallel engine's
// stages read them: each tet's four vertices as indices into the batch's DOF vector (every
// environment's DOFs one after the other, environment e's at [dof_begin(e), dof_begin(e + 1)),
// offsets by prefix sums), its environment, Dm^-1, rest volume and Lame parameters; and, per
// FEM vertex, the (tet, corner) slots that touch it, so that a gather sums a vertex's share of
// the tets' gradients in a fixed order (no atomics: the same sum on every launcher).
// Host-built, from plain arrays (no Model), so that the device check builds it too.
#include <vector>

namespace grip::solver::parallel {

// What a stage reads of the tets: raw pointers into host or device memory.
struct TetBuffers {
  int count = 0;
  const int* dofs = nullptr;                   // 4 per tet: each vertex's first DOF in the batch
  const int* environment = nullptr;            // per tet
  const double* rest_shape_inverse = nullptr;  // 9 per tet, Dm^-1 column-major
  const double* rest_volume = nullptr;         // per tet
  const double* mu = nullptr;                  // per tet, stable Neo-Hookean (kernels)
  const double* lambda = nullptr;              // per tet
  const double* damping = nullptr;             // per tet, Rayleigh beta (s); 0: undamped
};

// An FEM body's material, as solver::Material gives it.
struct FemMaterial {
  double youngs = 0.0;  // Pa
  double poisson = 0.0;
  double density = 0.0;  // kg/m^3
  double damping = 0.0;  // s, Rayleigh stiffness-proportional beta
};

// Per FEM vertex: its first DOF in the batch, its environment and its lumped mass (a quarter of
// each touching tet's rest mass, summed in tet order as FemBodies sums it).
struct VertexBuffers {
  int count = 0;
  const int* dof = nullptr;
  const int* environment = nullptr;
  const double* mass = nullptr;
};

// Per FEM vertex, the slots 4 t + c of the tets that touch it, in increasing order.
struct IncidenceBuffers {
  int count = 0;
  const int* vertex_dof = nullptr;  // per vertex: its first DOF in the batch
  const int* begin = nullptr;       // count + 1 offsets into slots
  const int* slots = nullptr;
};

class FemBatch {
 public:
  // Starts the next environment; its DOFs follow the previous one's.
  void begin_environment(int dof_count);
  // Adds an FEM body of the environment begun last: `rest` holds its vertices' rest positions
  // (3 each) and `tets` their indices (4 each, positively oriented); `first_dof` is its first
  // DOF within the environment. Throws std::invalid_argument for a flat or inverted tet, or a
  // vertex that no tet touches.
  void add_body(int first_dof, const std::vector<double>& rest, const std::vector<int>& tets,
                const FemMaterial& material);
  // Builds the vertices' incidence; call once every environment is in.
  void finish();

  int environment_count() const { return static_cast<int>(dof_begin_.size()) - 1; }
  int dof_count() const { return dof_begin_.back(); }
  // environment_count() + 1 offsets into the batch's DOFs, its tets and its FEM vertices.
  const std::vector<int>& dof_begin() const { return dof_begin_; }
  const std::vector<int>& tet_begin() const { return tet_begin_; }
  const std::vector<int>& vertex_begin() const { return vertex_begin_; }

  // Views of the host arrays.
  TetBuffers tets() const;
  VertexBuffers vertices() const;
  IncidenceBuffers incidence() const;

  // The arrays themselves, for copying to a device.
  const std::vector<int>& tet_dofs() const { return tet_dofs_; }
  const std::vector<int>& tet_environment() const { return tet_environment_; }
  const std::vector<double>& rest_shape_inverse() const { return rest_shape_inverse_; }
  const std::vector<double>& rest_volume() const { return rest_volume_; }
  const std::vector<double>& mu() const { return mu_; }
  const std::vector<double>& lambda() const { return lambda_; }
  const std::vector<double>& damping() const { return damping_; }
  const std::vector<int>& vertex_dof() const { return vertex_dof_; }
  const std::vector<int>& vertex_environment() const { return vertex_environment_; }
  const std::vector<double>& vertex_mass() const { return vertex_mass_; }
  const std::vector<int>& incidence_begin() const { return incidence_begin_; }
  const std::vector<int>& incidence_slots() const { return incidence_slots_; }

 private:
  std::vector<int> dof_begin_{0};
  std::vector<int> tet_begin_{0};
  std::vector<int> tet_dofs_;
  std::vector<int> tet_environment_;
  std::vector<double> rest_shape_inverse_;
  std::vector<double> rest_volume_;
  std::vector<double> mu_;
  std::vector<double> lambda_;
  std::vector<double> damping_;
  std::vector<int> vertex_begin_{0};
  std::vector<int> vertex_dof_;
  std::vector<int> vertex_environment_;
  std::vector<double> vertex_mass_;
  std::vector<int> incidence_begin_;
  std::vector<int> incidence_slots_;
};

}  // namespace grip::solver::parallel
