#pragma once
// The job's PETSc groups ([farm] petsc_group_ranks, petsc_groups): ranks that solve the big
// Newton systems of their leader's trials together through PETSc (farm/petsc), while the farm's
// other ranks keep taking work units alone. The groups are the communicator's last
// groups x group_ranks ranks; each group's lowest rank is its leader: it claims work units as
// any rank does, on one thread, and hands the group every system of the models too big for one
// rank (by the factor CHOLMOD would need, or by DOFs). The others (its members) take no work unit:
// they serve the leader's solves until it has no more (docs/farm.md, "PETSc groups").
#include <mpi.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "farm/job.hpp"
#include "farm/petsc/petsc_session.hpp"
#include "farm/petsc/petsc_system_solver.hpp"
#include "solver/linear/linear_system_solver.hpp"
#include "solver/model/model.hpp"

namespace grip::farm {

// Throws config::ConfigError at the job's key when the groups need more ranks than `comm` has:
// checked on every rank before any work.
void check_petsc_groups(const PetscGroupSetting& setting, MPI_Comm comm);

// The job's rule: whether the trials of `model` go to a group, by CHOLMOD's factor of its
// contact-free pattern (Model::contact_free_factor_bytes, a symbolic analysis) or, if the job
// sets min_dofs, by its DOFs.
bool too_big_for_one_rank(const PetscGroupSetting& setting, const solver::Model& model);

class PetscGroups {
 public:
  // Collective over `comm`, after check_petsc_groups passed. Without groups in the setting it
  // does nothing (no PETSc at all).
  // `petsc_options`: PETSc's command-line options (grip farm ... -- OPTIONS).
  PetscGroups(const PetscGroupSetting& setting, const std::vector<std::string>& petsc_options,
              MPI_Comm comm);
  ~PetscGroups();
  PetscGroups(const PetscGroups&) = delete;
  PetscGroups& operator=(const PetscGroups&) = delete;

  // A group member that is not its leader: it serves, and takes no work unit.
  bool member() const { return solver_ && !leader_; }
  bool leader() const { return leader_; }
  // This rank's group solver if it leads a group, else null.
  std::shared_ptr<solver::LinearSystemSolver> leader_solver() const;

  // A member: takes part in its leader's solves until the leader calls release().
  void serve();
  // A leader, once it claims no more work units: ends its members' serve(). Other ranks: nothing.
  void release();
  // Collective over the communicator: the systems every group solved.
  std::uint64_t total_solves(MPI_Comm comm) const;

 private:
  std::optional<PetscSession> session_;
  MPI_Comm group_ = MPI_COMM_NULL;
  std::shared_ptr<PetscSystemSolver> solver_;
  bool leader_ = false;
};

}  // namespace grip::farm
