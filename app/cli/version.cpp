#include "app/cli/version.hpp"

#include <CGAL/version.h>
#include <hdf5.h>
#include <mpi.h>
#include <petscversion.h>

#include <Eigen/Core>
#include <sstream>

namespace grip {

const char* version() { return GRIP_VERSION; }

std::string version_report() {
  // MPI_Get_library_version may be called before MPI_Init (MPI-3).
  char mpi_library[MPI_MAX_LIBRARY_VERSION_STRING];
  int length = 0;
  MPI_Get_library_version(mpi_library, &length);
  std::string mpi(mpi_library, static_cast<std::size_t>(length));
  mpi = mpi.substr(0, mpi.find_first_of(",\n"));

  std::ostringstream out;
  out << "grip " << GRIP_VERSION << " (revision " << git_revision() << ")\n"
      << "  MPI    " << mpi << " (MPI standard " << MPI_VERSION << '.' << MPI_SUBVERSION << ")\n"
      << "  HDF5   " << H5_VERS_MAJOR << '.' << H5_VERS_MINOR << '.' << H5_VERS_RELEASE
#ifdef H5_HAVE_PARALLEL
      << " (parallel)\n"
#else
      << " (serial)\n"
#endif
      << "  PETSc  " << PETSC_VERSION_MAJOR << '.' << PETSC_VERSION_MINOR << '.'
      << PETSC_VERSION_SUBMINOR << '\n'
      << "  CGAL   " << CGAL_VERSION_STR << '\n'
      << "  Eigen  " << EIGEN_WORLD_VERSION << '.' << EIGEN_MAJOR_VERSION << '.'
      << EIGEN_MINOR_VERSION << '\n';
  return out.str();
}

}  // namespace grip
