#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and runs the most complete job
# grip can do today: it prepares the assets (every object category and gripper) and simulates
# the example scenes with the IPC solver, checking the invariants after every step. Outputs
# land in out/ (override with GRIP_OUT).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/build.sh"
grip="$root/build/grip"
out=${GRIP_OUT:-$root/out}
mkdir -p "$out/reports"

"$grip" --version
"$grip" asset gallery --out "$out/gallery"
for scene in "$root"/examples/scenes/*.toml; do
  name=$(basename "$scene" .toml)
  "$grip" simulate "$scene" --report "$out/reports/$name.json"
done
echo
echo "Assets in $out/gallery, simulation reports in $out/reports; for example $name:"
cat "$out/reports/$name.json"
