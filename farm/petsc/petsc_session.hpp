#pragma once
// PETSc initialized for as long as a PetscSession lives, with the options grip's command line
// passes through (everything after a lone `--`) in PETSc's options database.
#include <mpi.h>

#include <string>
#include <vector>

namespace grip::farm {

class PetscSession {
 public:
  // Initializes PETSc over `comm` (MPI must already be initialized, and PETSc not) with
  // `options` in command-line form, e.g. {"-ksp_type", "cg", "-pc_type", "gamg"}.
  explicit PetscSession(const std::vector<std::string>& options, MPI_Comm comm = MPI_COMM_WORLD);
  ~PetscSession();  // PetscFinalize; MPI stays initialized
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;

 private:
  std::vector<std::string> arguments_;  // PETSc may keep pointers into argv
  std::vector<char*> argv_;
};

}  // namespace grip::farm
