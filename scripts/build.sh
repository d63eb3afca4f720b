#!/usr/bin/env bash
# Installs what is missing, configures and builds grip (Release) in build/.
# Usage: scripts/build.sh [extra cmake -D options]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/install-deps.sh"
if [[ ! -f "$root/build/build.ninja" || $# -gt 0 ]]; then
  cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
fi
cmake --build "$root/build" --parallel "$(nproc)"
