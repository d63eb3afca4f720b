#include "farm/petsc/petsc_session.hpp"

#include <petscsys.h>

#include <stdexcept>

namespace grip::farm {

PetscSession::PetscSession(const std::vector<std::string>& options, MPI_Comm comm) {
  int mpi_initialized = 0;
  MPI_Initialized(&mpi_initialized);
  PetscBool petsc_initialized = PETSC_FALSE;
  PetscInitialized(&petsc_initialized);
  if (!mpi_initialized || petsc_initialized) {
    throw std::logic_error("PetscSession needs MPI initialized and PETSc not yet initialized");
  }
  arguments_.push_back("grip");
  arguments_.insert(arguments_.end(), options.begin(), options.end());
  for (std::string& argument : arguments_) argv_.push_back(argument.data());
  argv_.push_back(nullptr);
  int argc = static_cast<int>(arguments_.size());
  char** argv = argv_.data();
  PETSC_COMM_WORLD = comm;
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) {
    throw std::runtime_error("PetscInitialize failed");
  }
}

PetscSession::~PetscSession() { PetscFinalize(); }

}  // namespace grip::farm
