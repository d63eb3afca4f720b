#pragma once
// The collision vertices of a whole batch of environments, as the data-parallel engine maps
// between them and the DOFs (map_stages.hpp): per vertex how it moves (with its own 3 DOFs, an
// FEM vertex; with its affine body's 12, at a rest point about the body's centre of mass; or
// with no DOF, where a script puts it), its environment and the DOF block it moves with. A DOF
// block is an FEM vertex or an affine body: what a contact's gradient is gathered into. Each
// environment's vertices are numbered after the previous ones' (as ContactPairs numbers them)
// and its DOFs after the previous ones' (as FemBatch and AffineBatch lay them). Host-built
// from plain values (no Model).
#include <vector>

namespace grip::solver::parallel {

enum class VertexMotion : unsigned char { kFem = 0, kAffine = 1, kScripted = 2 };

// What a stage reads of the collision vertices: raw pointers into host or device memory.
struct CollisionVertexBuffers {
  int count = 0;
  const unsigned char* motion = nullptr;  // per vertex, a VertexMotion
  const int* dof = nullptr;          // per vertex: its first DOF (FEM) or its body's (affine); -1
  const double* rest = nullptr;      // 3 per vertex: an affine vertex's rest point
  const int* environment = nullptr;  // per vertex
};

// The DOF blocks and, per block, the contact slots (4 k + c: corner c of pair k) that touch it,
// in increasing order (contact_incidence).
struct ContactIncidenceBuffers {
  int count = 0;                    // blocks
  const int* block_dof = nullptr;   // per block: its first DOF
  const int* block_size = nullptr;  // per block: 3 (an FEM vertex) or 12 (an affine body)
  const int* begin = nullptr;       // count + 1 offsets into slots
  const int* slots = nullptr;
};

class CollisionBatch {
 public:
  // Starts the next environment; its DOFs follow the previous one's.
  void begin_environment(int dof_count);
  // The next collision vertex of the environment begun last. `first_dof` is within the
  // environment: the FEM vertex's own, or its affine body's (a body's vertices come one after
  // another and share its block).
  void add_fem_vertex(int first_dof);
  void add_affine_vertex(int body_first_dof, double x, double y, double z);
  void add_scripted_vertex();

  int environment_count() const { return static_cast<int>(dof_begin_.size()) - 1; }
  int vertex_count() const { return static_cast<int>(motion_.size()); }
  int block_count() const { return static_cast<int>(block_dof_.size()); }
  // environment_count() + 1 offsets into the batch's DOFs and its collision vertices.
  const std::vector<int>& dof_begin() const { return dof_begin_; }
  const std::vector<int>& vertex_begin() const { return vertex_begin_; }
  const std::vector<int>& block_dof() const { return block_dof_; }
  const std::vector<int>& block_size() const { return block_size_; }

  CollisionVertexBuffers vertices() const;

  // The arrays themselves, for copying to a device.
  const std::vector<unsigned char>& motion() const { return motion_; }
  const std::vector<int>& dof() const { return dof_; }
  const std::vector<double>& rest() const { return rest_; }
  const std::vector<int>& environment() const { return environment_; }
  // Per vertex: its DOF block, -1 for a scripted vertex (what the host's incidence reads).
  const std::vector<int>& block() const { return block_; }

 private:
  void add(VertexMotion motion, int dof, int block_size, double x, double y, double z);

  std::vector<int> dof_begin_{0};
  std::vector<int> vertex_begin_{0};
  std::vector<unsigned char> motion_;
  std::vector<int> dof_;
  std::vector<double> rest_;
  std::vector<int> environment_;
  std::vector<int> block_;
  std::vector<int> block_dof_;
  std::vector<int> block_size_;
};

// Which contact slots touch each DOF block, for `pair_count` pairs of 4 collision vertices each
// (`pair_vertex`, in the batch's numbering): the order a gather sums them in. Rebuilt whenever
// the pairs change. Host-built for now (a device would sort the slots by block).
struct ContactIncidence {
  std::vector<int> begin;  // block_count + 1 offsets
  std::vector<int> slots;
};
ContactIncidence contact_incidence(const CollisionBatch& batch, const int* pair_vertex,
                                   int pair_count);
// Views of the batch's blocks and the incidence's host arrays.
ContactIncidenceBuffers incidence_buffers(const CollisionBatch& batch,
                                          const ContactIncidence& incidence);

}  // namespace grip::solver::parallel
