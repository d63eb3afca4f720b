#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and runs the demo job
# (jobs/demo.toml) as one process on all cores: objects prepared, grasp candidates synthesized,
# every candidate's trial simulated with the IPC solver, all written to one HDF5 dataset, then
# its summary. Run again, it resumes the same dataset (nothing left: it prints the summary).
# The dataset goes to out/demo/ (override the folder with GRIP_OUT).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/build.sh" --target grip  # the tests and benchmarks are scripts/test.sh's
grip="$root/build/grip"
dataset=${GRIP_OUT:-$root/out}/demo/dataset.h5

"$grip" --version
resume=()
if [ -e "$dataset" ]; then resume=(--resume); fi
cd "$root"
"$grip" farm jobs/demo.toml --output "$dataset" "${resume[@]}"
echo
echo "The dataset is $dataset; 'build/grip inspect $dataset' summarizes it again and"
echo "examples/read_dataset.py shows how to read it from Python (h5py)."
# One trial drawn to a PNG beside the dataset (docs/dataset-format.md#a-picture-of-a-trial).
/usr/bin/python3 examples/render_grasp.py "$dataset" --out "$(dirname "$dataset")/grasp.png"
