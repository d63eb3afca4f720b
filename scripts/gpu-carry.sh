#!/usr/bin/env bash
# Copies what scripts/gpu-check.sh needs beyond CUDA into .gpu-carry/ (ignored by git): Eigen's
# headers, for a GPU machine that has nvcc but none of Debian's -dev packages. Run it on a
# machine with grip's dependencies installed (scripts/install-deps.sh), then take the checkout
# with .gpu-carry/ to the GPU machine.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
eigen=/usr/include/eigen3
[[ -f $eigen/Eigen/Core ]] || { echo "gpu-carry: no Eigen in $eigen (scripts/install-deps.sh)" >&2; exit 2; }
rm -rf "$root/.gpu-carry"
mkdir -p "$root/.gpu-carry"
cp -r "$eigen" "$root/.gpu-carry/eigen3"
echo "gpu-carry: $(du -sh "$root/.gpu-carry" | cut -f1) in .gpu-carry/"
