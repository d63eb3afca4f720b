#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and runs the most complete job
# grip can do today: it prepares the assets (every object category and gripper), simulates the
# example scenes with the IPC solver as one batch of environments (checking the invariants after
# every step), then synthesizes grasp candidates for a cylinder and runs their trials as one
# batch. Outputs land in out/ (override with GRIP_OUT).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/build.sh"
grip="$root/build/grip"
out=${GRIP_OUT:-$root/out}
mkdir -p "$out/reports" "$out/candidates"

"$grip" --version
"$grip" asset gallery --out "$out/gallery"
"$grip" simulate "$root"/examples/scenes/*.toml --report "$out/reports/scenes.json"
"$grip" synth --object cylinder --gripper parallel-jaw --count 8 --seed 1 \
  --out "$out/candidates/cylinder-parallel-jaw.txt"
"$grip" trial --object cylinder --seed 1 --gripper parallel-jaw \
  --candidates "$out/candidates/cylinder-parallel-jaw.txt" --index 0-7 \
  --report "$out/reports/trials-cylinder-parallel-jaw.json"
echo
echo "Assets in $out/gallery; the simulation report (one entry per scene) is"
echo "$out/reports/scenes.json; grasp candidates are in $out/candidates and their trials'"
echo "verdicts, D1/D2 and closing forces in $out/reports/trials-cylinder-parallel-jaw.json"
