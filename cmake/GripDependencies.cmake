# Every third-party dependency of grip, found once here. All come from Debian 12 packages
# (scripts/install-deps.sh installs them).

find_package(MPI REQUIRED COMPONENTS C CXX)

# HDF5 must be the parallel (MPI-IO) build: the dataset is written collectively by all ranks.
set(HDF5_PREFER_PARALLEL TRUE)
find_package(HDF5 REQUIRED COMPONENTS C)
if(NOT HDF5_IS_PARALLEL)
  message(FATAL_ERROR
    "grip needs the parallel (MPI-IO) build of HDF5, but CMake found a serial one "
    "(${HDF5_C_INCLUDE_DIRS}). Install libhdf5-openmpi-dev (scripts/install-deps.sh does) "
    "and remove any CMakeCache.txt that remembers the serial one.")
endif()
add_library(grip_hdf5 INTERFACE)
target_include_directories(grip_hdf5 SYSTEM INTERFACE ${HDF5_C_INCLUDE_DIRS})
target_compile_definitions(grip_hdf5 INTERFACE ${HDF5_C_DEFINITIONS})
target_link_libraries(grip_hdf5 INTERFACE ${HDF5_C_LIBRARIES} MPI::MPI_C)

find_package(PkgConfig REQUIRED)
pkg_check_modules(PETSC REQUIRED IMPORTED_TARGET PETSc)
find_path(METIS_INCLUDE_DIR metis.h REQUIRED)
find_library(METIS_LIBRARY metis REQUIRED)
add_library(grip_metis INTERFACE)
target_include_directories(grip_metis SYSTEM INTERFACE ${METIS_INCLUDE_DIR})
target_link_libraries(grip_metis INTERFACE ${METIS_LIBRARY})

find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(CGAL REQUIRED)
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
add_library(grip_cholmod INTERFACE)
target_include_directories(grip_cholmod SYSTEM INTERFACE ${CHOLMOD_INCLUDE_DIR})
target_link_libraries(grip_cholmod INTERFACE ${CHOLMOD_LIBRARY})

find_package(spdlog REQUIRED)
find_package(TBB REQUIRED)
pkg_check_modules(TOMLPP REQUIRED IMPORTED_TARGET tomlplusplus)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(urdfdom REQUIRED)
find_package(Threads REQUIRED)
# SHA-256 of job files (the dataset's job id); libssl-dev also comes with parallel HDF5.
find_package(OpenSSL REQUIRED COMPONENTS Crypto)

if(GRIP_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(GRIP_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
