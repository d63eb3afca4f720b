#!/usr/bin/env bash
# Builds grip and its test suite with AddressSanitizer and UndefinedBehaviorSanitizer in
# build-fuzz/, the instrumented tree the fuzz targets use (scripts/instrumented-tree.sh: clang
# 14, every module instrumented once for both), and runs the suite through ctest. Any sanitizer
# report fails its test.
# Usage: scripts/sanitize.sh [ctest options, e.g. -R '^io_' or -L unit]
# GRIP_SANITIZE_TARGETS="a b" builds only those targets (pair it with a ctest -R that selects
# their tests); the default builds everything.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$root/scripts/instrumented-tree.sh"
"$root/scripts/install-deps.sh"
configure_instrumented_tree ON
targets=()
for t in ${GRIP_SANITIZE_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build" --parallel "$(nproc)" "${targets[@]}"

# Leaks are checked, except those in the system libraries listed in lsan.supp (Open MPI keeps
# its allocations until exit). Those suppressions match only on full stacks: hence the slow
# unwinder, and Open MPI keeps its plugins loaded so that their frames keep their names.
# UBSan findings stop the program so ctest sees them.
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:fast_unwind_on_malloc=0"
export OMPI_MCA_mca_base_component_disable_dlclose=1
export LSAN_OPTIONS="suppressions=$root/scripts/sanitize/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$root/scripts/sanitize/ubsan.supp"
ctest --test-dir "$build" --output-on-failure --timeout 1800 --parallel "$(nproc)" "$@"
