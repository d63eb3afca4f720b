#include "farm/petsc_groups.hpp"

#include <algorithm>

#include "src/config/config.hpp"

namespace grip::farm {

void check_petsc_groups(const PetscGroupSetting& setting, MPI_Comm comm) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  if (setting.ranks() <= ranks) return;
  const std::string groups =
      setting.groups == 1 ? "a group" : std::to_string(setting.groups) + " groups";
  throw config::ConfigError(setting.location + ": key 'farm.petsc_group_ranks' asks for " + groups +
                            " of " + std::to_string(setting.group_ranks) + " rank(s), " +
                            std::to_string(setting.ranks()) + " in all, but this run has " +
                            std::to_string(ranks) + " rank(s): run under mpirun -np " +
                            std::to_string(setting.ranks()) + " or more, or ask for fewer ranks");
}

bool too_big_for_one_rank(const PetscGroupSetting& setting, const solver::Model& model) {
  if (setting.min_dofs > 0 && model.dof_count() >= setting.min_dofs) return true;
  return model.contact_free_factor_bytes() >= setting.min_factor_bytes();
}

PetscGroups::PetscGroups(const PetscGroupSetting& setting,
                         const std::vector<std::string>& petsc_options, MPI_Comm comm) {
  if (setting.group_ranks == 0) return;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  // PETSc's own signal handler would take SIGTERM and SIGINT from the farm's stop handling.
  std::vector<std::string> options = petsc_options;
  if (std::find(options.begin(), options.end(), "-no_signal_handler") == options.end()) {
    options.push_back("-no_signal_handler");
  }
  session_.emplace(options, comm);
  const int first = ranks - setting.ranks();
  const int color = rank >= first ? (rank - first) / setting.group_ranks : MPI_UNDEFINED;
  MPI_Comm_split(comm, color, rank, &group_);
  if (group_ == MPI_COMM_NULL) return;
  solver_ = std::make_shared<PetscSystemSolver>(group_, "");
  leader_ = solver_->rank() == 0;
}

PetscGroups::~PetscGroups() {
  solver_.reset();  // a leader's stop(), if release() did not come
  if (group_ != MPI_COMM_NULL) MPI_Comm_free(&group_);
}

std::shared_ptr<solver::LinearSystemSolver> PetscGroups::leader_solver() const {
  return leader_ ? solver_ : nullptr;
}

void PetscGroups::serve() {
  if (member()) solver_->serve();
}

void PetscGroups::release() {
  if (leader_) solver_->stop();
}

std::uint64_t PetscGroups::total_solves(MPI_Comm comm) const {
  const std::uint64_t mine = leader_ ? solver_->solves() : 0;
  std::uint64_t total = 0;
  MPI_Allreduce(&mine, &total, 1, MPI_UINT64_T, MPI_SUM, comm);
  return total;
}

}  // namespace grip::farm
