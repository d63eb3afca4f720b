#!/usr/bin/env bash
# The device check: builds grip-gpu-check from this tree with nvcc alone (CUDA and Eigen's
# headers: from .gpu-carry/, which scripts/gpu-carry.sh fills, or the system's), runs it, and
# writes gpu-check.json, gpu-check.md and the GPU's nvidia-smi report into OUTDIR. It compares
# the data-parallel engine's stages (elastic, FEM inertia, barrier, CCD, friction, affine, map,
# Hessian blocks, block-Jacobi CG, broad phase, step halving, incremental potential and
# sufficient decrease) on the GPU with the host launcher on the same batches, and times them
# at 1 to 512 environments (docs/architecture.md, "Engines"). Sized to
# finish well inside 8 minutes: the build takes about 3 minutes of one core, the host's share of
# the largest batch (1.2 million tets, 262,144 pairs and as many friction contacts, one core)
# well under one. Exit status:
# grip-gpu-check's (0 all within tolerance, 1 a difference outside it, 2 no device), or the
# build's.
#   scripts/gpu-check.sh OUTDIR [grip-gpu-check options]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:?usage: scripts/gpu-check.sh OUTDIR [--sizes 1,8,64,256,512] [--repeats 5]}
shift
mkdir -p "$out"
eigen=$root/.gpu-carry/eigen3
[[ -f $eigen/Eigen/Core ]] || eigen=/usr/include/eigen3
[[ -f $eigen/Eigen/Core ]] || { echo "gpu-check: no Eigen headers: run scripts/gpu-carry.sh first" >&2; exit 2; }
nvcc=$(command -v nvcc || echo /usr/local/cuda/bin/nvcc)
mkdir -p "$root/build-gpu"
# The flags solver/CMakeLists.txt gives grip-gpu-check.
start=$(date +%s)
"$nvcc" -std=c++20 -O3 -arch=sm_90 -I"$root" -isystem "$eigen" --expt-relaxed-constexpr \
  -diag-suppress=20012 -Werror=all-warnings -Xcompiler=-Wall,-Wextra,-Werror \
  "$root/solver/parallel/cuda/device_check.cu" "$root/solver/parallel/cuda/broad_phase_check.cu" \
  "$root/solver/parallel/cuda/potential_check.cu" \
  "$root/solver/parallel/fem_batch.cpp" "$root/solver/parallel/surface_batch.cpp" \
  "$root/solver/parallel/broad_phase.cpp" \
  "$root/solver/parallel/affine_batch.cpp" "$root/solver/parallel/collision_batch.cpp" \
  "$root/solver/parallel/block_assembly.cpp" "$root/solver/parallel/block_pcg.cpp" \
  "$root/solver/parallel/contact_stages.cpp" "$root/solver/parallel/friction_stages.cpp" \
  -o "$root/build-gpu/grip-gpu-check"
echo "gpu-check: built in $(($(date +%s) - start)) s"
nvidia-smi >"$out/nvidia-smi.txt" 2>&1 || true
"$root/build-gpu/grip-gpu-check" "$out" "$@"
