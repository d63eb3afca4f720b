#!/usr/bin/env bash
# grip trial takes its object and gripper from the candidate file: run without --object it
# builds the candidates' object; told another object, seed or gripper it refuses in one line
# naming the file and the option, and writes nothing; --device host runs it on the data-parallel
# engine, --device cuda is refused.
set -euo pipefail
grip=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$grip" synth --object plate --gripper parallel-jaw --count 1 --seed 1 --out "$dir/c.txt" >/dev/null

"$grip" trial --candidates "$dir/c.txt" --threads 1 --report "$dir/r.json" 2>/dev/null
grep -q '"object": "plate"' "$dir/r.json" || { echo "FAIL: the report does not name the plate"; exit 1; }
grep -q '"gripper": "parallel-jaw"' "$dir/r.json" || { echo "FAIL: no gripper from the file"; exit 1; }
if grep -q initial_penetration "$dir/r.json"; then echo "FAIL: another object was built"; exit 1; fi

refused() {  # refused WHAT EXPECTED-TEXT ARGS...
  local what=$1 expected=$2; shift 2
  if "$grip" trial --candidates "$dir/c.txt" --report "$dir/bad.json" "$@" 2>"$dir/err"; then
    echo "FAIL: $what was accepted"; exit 1
  fi
  if [ -e "$dir/bad.json" ]; then echo "FAIL: $what wrote a report"; exit 1; fi
  if [ "$(grep -c . "$dir/err")" -ne 1 ] || ! grep -q -- "$expected" "$dir/err"; then
    echo "FAIL: $what: expected one line with '$expected', got:"; cat "$dir/err"; exit 1
  fi
}
refused "another object" "c.txt: the candidates were synthesized with --object plate, not box" --object box
refused "another seed" "synthesized with --seed 1, not 2" --seed 2
refused "another gripper" "synthesized with --gripper parallel-jaw, not fin-ray" --gripper fin-ray
refused "--device cuda" "--device cuda: this grip has no CUDA engine to step environments on yet" --device cuda
# The data-parallel engine on the CPU: its report names it.
"$grip" trial --candidates "$dir/c.txt" --threads 1 --device host --report "$dir/host.json" 2>/dev/null
grep -q '"device": "host"' "$dir/host.json" || { echo "FAIL: the report does not name the engine"; exit 1; }
echo "ok"
