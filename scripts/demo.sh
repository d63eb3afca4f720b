#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and runs the most complete job
# grip can do today: it prepares the assets (every object category and gripper) and simulates
# the example scenes with the IPC solver as one batch of environments, checking the invariants
# after every step. Outputs land in out/ (override with GRIP_OUT).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/build.sh"
grip="$root/build/grip"
out=${GRIP_OUT:-$root/out}
mkdir -p "$out/reports"

"$grip" --version
"$grip" asset gallery --out "$out/gallery"
"$grip" simulate "$root"/examples/scenes/*.toml --report "$out/reports/scenes.json"
echo
echo "Assets in $out/gallery; the simulation report (one entry per scene) is $out/reports/scenes.json"
