#!/usr/bin/env bash
# grip simulate runs the example scenes on the CPU engine and on the data-parallel engine
# (--device host): on both every scene runs its steps, intersection-free at every step (the
# exact check) with every tet positively oriented, and the two agree on the closest contact
# and the worst tet to 1 %.
set -euo pipefail
grip=$1
examples=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for device in cpu host; do
  "$grip" -q simulate "$examples"/*.toml --threads 2 --device "$device" --report "$dir/$device.json"
done
/usr/bin/python3 - "$dir" <<'PY'
import json, sys
cpu, host = (json.load(open(f"{sys.argv[1]}/{d}.json"))["scenes"] for d in ("cpu", "host"))
assert len(cpu) == len(host) == 4, (len(cpu), len(host))
for c, h in zip(cpu, host):
    name = c["scene"]
    for r in (c, h):
        assert r["status"] == "ok" and r["intersection_free"] and r["min_volume_ratio"] > 0, (name, r)
    assert h["steps"] == c["steps"], (name, c["steps"], h["steps"])
    for key in ("min_distance", "min_volume_ratio"):
        assert abs(h[key] - c[key]) <= 0.01 * abs(c[key]), (name, key, c[key], h[key])
print("ok")
PY
