#!/bin/bash
# The same synthesized candidates on the CPU engine and on the data-parallel engine
# (grip trial --device cpu and --device host): per candidate both verdicts, D1, the closing
# forces, Newton and CG iterations and each engine's wall time, then how many verdicts agree.
#
#   scripts/compare-engines.sh OUT [GRIPPER] [COUNT] [CATEGORY:SEED ...]
#
# OUT: a folder for the candidate files and reports; GRIPPER: fin-ray (default), parallel-jaw,
# leap or a gripper description file (*.toml); COUNT: candidates per shape (default 4); shapes:
# categories and seeds (default box:4 cylinder:1 capsule:1 bottle:1, the labels benchmark's
# categories at the first seed of each that gives the fin-ray gripper candidates). Extra options for grip trial (--soft,
# --threads) go in GRIP_TRIAL_OPTIONS. The grip binary is $GRIP or build/grip.
set -euo pipefail
out=${1:?usage: scripts/compare-engines.sh OUT [GRIPPER] [COUNT] [CATEGORY:SEED ...]}
gripper=${2:-fin-ray}
count=${3:-4}
shift $(($# < 3 ? $# : 3))
shapes=("$@")
[ ${#shapes[@]} -gt 0 ] || shapes=(box:4 cylinder:1 capsule:1 bottle:1)
grip=${GRIP:-$(dirname "$0")/../build/grip}
read -r -a trial_options <<< "${GRIP_TRIAL_OPTIONS:-}"
# A described gripper's candidates name it "described": the trial needs its file again.
if [[ $gripper == *.toml ]]; then trial_options+=(--gripper "$gripper"); fi
mkdir -p "$out"
ran=()
for shape in "${shapes[@]}"; do
  category=${shape%%:*}
  seed=${shape##*:}
  name=$category-$seed
  # Synthesis exits 1 when it finds fewer candidates than asked (none on a shape wider than the
  # gripper opens); what it found is in the file it wrote.
  rm -f "$out/$name.txt"
  "$grip" -q synth --object "$category" --seed "$seed" --gripper "$gripper" --count "$count" \
    --out "$out/$name.txt" || [ -s "$out/$name.txt" ]
  found=$(awk '$1 == "count" { print $2 }' "$out/$name.txt")
  if [ "$found" -eq 0 ]; then
    echo "$name: no candidates for $gripper; left out" >&2
    continue
  fi
  ran+=("$shape")
  for device in cpu host; do
    "$grip" -q trial --candidates "$out/$name.txt" --index "0-$((found - 1))" --device "$device" \
      "${trial_options[@]}" --report "$out/$name-$device.json"
  done
done
[ ${#ran[@]} -gt 0 ] || { echo "no shape gave $gripper candidates" >&2; exit 1; }
/usr/bin/python3 - "$out" "${ran[@]}" <<'PY'
import json, sys
out, shapes = sys.argv[1], sys.argv[2:]
same = total = 0
print("| shape | candidate | CPU verdict | host verdict | D1 CPU / host | closing N, CPU | closing N, host | Newton CPU / host | CG host |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
walls = {"cpu": 0.0, "host": 0.0}
for shape in shapes:
    name = shape.replace(":", "-")
    reports = {d: json.load(open(f"{out}/{name}-{d}.json")) for d in ("cpu", "host")}
    for d in walls:
        walls[d] += reports[d]["wall_seconds"]
    for c, h in zip(reports["cpu"]["trials"], reports["host"]["trials"]):
        verdict = lambda r: r["status"] if r["failure"] == "none" else r["failure"]
        total += 1
        same += verdict(c) == verdict(h)
        forces = lambda r: " ".join(f"{f:.1f}" for f in r["closing_forces"])
        print(f"| {name} | {c['id']} | {verdict(c)} | {verdict(h)} | {c['d1']} / {h['d1']} | "
              f"{forces(c)} | {forces(h)} | {c['newton']['iterations']} / "
              f"{h['newton']['iterations']} | {h['linear_solves']['cg_iterations']} |")
print(f"\n{same} of {total} verdicts agree; wall time CPU engine {walls['cpu']:.1f} s, "
      f"data-parallel engine {walls['host']:.1f} s")
PY
