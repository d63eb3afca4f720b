# The git revision baked into `grip --version`, refreshed on every build (not only at
# configure time) and rewritten only when it changes, so an unchanged tree does not relink.
set(GRIP_REVISION_FILE ${CMAKE_BINARY_DIR}/generated/grip_revision.cpp)
add_custom_target(grip_revision_stamp
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${CMAKE_SOURCE_DIR} -DOUT=${GRIP_REVISION_FILE}
          -P ${CMAKE_SOURCE_DIR}/cmake/write_revision.cmake
  BYPRODUCTS ${GRIP_REVISION_FILE}
  COMMENT "Reading the git revision")
