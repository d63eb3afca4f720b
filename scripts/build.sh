#!/usr/bin/env bash
# Installs what is missing, configures and builds grip (Release) in build/: every target, or only
# the ones named with --target (scripts/demo.sh builds just the grip executable). Libraries are
# compiled in batches of sources (GRIP_UNITY_BUILD, docs/architecture.md), through ccache when it
# is installed.
# Usage: scripts/build.sh [--target NAME]... [extra cmake -D options]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
targets=()
while [[ $# -ge 2 && $1 == --target ]]; do
  targets+=(--target "$2")
  shift 2
done
"$root/scripts/install-deps.sh"
"$root/scripts/install-peers.sh"
# CUDA's toolkit installs nvcc outside the PATH; CMake builds the CUDA sources where it finds it.
if ! command -v nvcc >/dev/null && [[ -z ${CUDACXX:-} && -x /usr/local/cuda/bin/nvcc ]]; then
  export CUDACXX=/usr/local/cuda/bin/nvcc
fi
if [[ ! -f "$root/build/build.ninja" || $# -gt 0 ]]; then
  source "$root/scripts/ccache-launcher.sh"
  cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DGRIP_UNITY_BUILD=ON \
    "${launcher[@]}" "$@" >/dev/null
fi
cmake --build "$root/build" --parallel "$(nproc)" "${targets[@]}"
