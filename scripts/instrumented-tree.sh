# Sourced by scripts/fuzz.sh and scripts/sanitize.sh: the one instrumented build tree they share,
# build-fuzz/ (clang 14, AddressSanitizer and UndefinedBehaviorSanitizer on every module, plus
# libFuzzer's coverage instrumentation; -DGRIP_FUZZ=ON), configured if it is not yet. With
# tests=ON the test suite is configured in it too (scripts/sanitize.sh); the fuzz targets never
# need it. The sanitizers instrument host code only: no CUDA here. Expects `root`; sets `build`.
build="$root/build-fuzz"
configure_instrumented_tree() {
  local tests="$1"
  source "$root/scripts/ccache-launcher.sh"
  if [[ ! -f "$build/build.ninja" ]]; then
    cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
          -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DGRIP_FUZZ=ON \
          -DGRIP_BUILD_TESTS="$tests" -DGRIP_BUILD_BENCH=OFF -DGRIP_CUDA=OFF "${launcher[@]}" >/dev/null
  elif [[ $tests == ON ]]; then
    cmake -S "$root" -B "$build" -DGRIP_BUILD_TESTS=ON >/dev/null
  fi
}
