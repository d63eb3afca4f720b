# Sourced by the build scripts: sets `launcher` to the CMake options that compile through ccache
# when it is installed (empty otherwise), with paths relative to the checkout so that clones
# share the cache.
launcher=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$root}"
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
