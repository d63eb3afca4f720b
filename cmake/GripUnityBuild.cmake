# GRIP_UNITY_BUILD: every library and the grip and grip-bench executables compiled as a few batches of their
# sources ("unity" builds). Separate translation units each parse and instantiate the same Eigen
# and CGAL templates again; batches do it once, so a clean build of grip takes about 30% less
# CPU (docs/architecture.md). Same flags, same code, no warning added. scripts/build.sh turns it
# on (the newcomer's first build); without it, editing one file recompiles only that file. Tests
# are compiled file by file either way. A source whose file-local names clash with another's in
# its batch is compiled alone.
option(GRIP_UNITY_BUILD "Compile libraries and grip in batches of sources (faster clean builds)"
       OFF)
if(NOT GRIP_UNITY_BUILD)
  return()
endif()

function(grip_unity_build dir)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "STATIC_LIBRARY" OR target MATCHES "^grip(-bench)?$")
      set_target_properties(${target} PROPERTIES UNITY_BUILD ON)
    endif()
  endforeach()
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(subdir IN LISTS subdirs)
    grip_unity_build(${subdir})
  endforeach()
endfunction()

foreach(module solver src io farm app bench)
  grip_unity_build(${PROJECT_SOURCE_DIR}/${module})
endforeach()

# Compiled alone: file-local helpers or aliases named like another file's of the same batch
# (sim_parameters, triangle_tree); a class whose members have file-local types, which GCC warns
# about (-Wsubobject-linkage) once the file is included into a batch (petsc_system_solver).
foreach(source src/scene/sim_parameters.cpp src/synth/triangle_tree.cpp
               farm/petsc/petsc_system_solver.cpp)
  get_filename_component(dir ${PROJECT_SOURCE_DIR}/${source} DIRECTORY)
  set_source_files_properties(${PROJECT_SOURCE_DIR}/${source} DIRECTORY ${dir}
                              PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
endforeach()
# The broad phase too: in a batch, GCC stops inlining its inner loops' box and distance tests.
set_source_files_properties(${PROJECT_SOURCE_DIR}/solver/contact/candidates.cpp
                            DIRECTORY ${PROJECT_SOURCE_DIR}/solver
                            PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
