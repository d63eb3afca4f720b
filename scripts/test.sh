#!/usr/bin/env bash
# The README's test command (and CI's): installs, builds, then runs the whole test suite,
# unit tests and MPI tests, through ctest.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/build.sh"
ctest --test-dir "$root/build" --output-on-failure --timeout 600 --parallel "$(nproc)" "$@"
