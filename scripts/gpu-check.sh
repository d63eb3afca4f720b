#!/usr/bin/env bash
# The device check: builds grip-gpu-check from this tree with nvcc alone (CUDA and Eigen's
# headers: from .gpu-carry/, which scripts/gpu-carry.sh fills, or the system's), runs it, and
# writes gpu-check.json, gpu-check.md and the GPU's nvidia-smi report into OUTDIR. It compares
# the data-parallel engine's stages (elastic, FEM inertia, barrier, CCD, friction, affine, map,
# Hessian blocks, two-level CG, broad phase, step halving, incremental potential, Newton
# system, sufficient decrease, dense Cholesky) on the GPU with the host launcher on the same
# batches, and times them at 1 to 512 environments (docs/architecture.md, "Engines"). Sized to
# finish well inside 8 minutes: on an H200 machine with 16 cores it built in 82 s and ran in
# 106 s (docs/results/gpu.md); the build is about 4 minutes of one core, its sources compiled
# side by side, and the host's share of the largest batch (1.2 million tets, 262,144 pairs and
# as many friction contacts) 31 s of one core in its stages. Exit status:
# grip-gpu-check's (0 all within tolerance, 1 a difference outside it, 2 no device), else 3
# when memcheck finds an error, or the build's.
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
# The flags solver/CMakeLists.txt gives grip-gpu-check. Each source compiles in a job of its
# own (nvcc takes several files one after the other), then one link.
flags=(-std=c++20 -O3 -arch=sm_90 -I"$root" -isystem "$eigen" --expt-relaxed-constexpr
  -diag-suppress=20012 -Werror=all-warnings -Xcompiler=-Wall,-Wextra,-Werror)
sources=(solver/parallel/cuda/device_check.cu solver/parallel/cuda/broad_phase_check.cu
  solver/parallel/cuda/potential_check.cu solver/parallel/cuda/dense_check.cu
  solver/parallel/fem_batch.cpp
  solver/parallel/surface_batch.cpp solver/parallel/broad_phase.cpp
  solver/parallel/affine_batch.cpp solver/parallel/collision_batch.cpp
  solver/parallel/block_assembly.cpp solver/parallel/block_pcg.cpp solver/parallel/coarse_space.cpp
  solver/parallel/contact_stages.cpp solver/parallel/friction_stages.cpp
  solver/parallel/derivative_stages.cpp solver/parallel/step_start_stages.cpp)
start=$(date +%s)
objects=() jobs=()
for source in "${sources[@]}"; do
  object=$root/build-gpu/$(basename "${source%.*}").o
  "$nvcc" "${flags[@]}" -c "$root/$source" -o "$object" &
  jobs+=($!) objects+=("$object")
done
failed=0
for job in "${jobs[@]}"; do wait "$job" || failed=$?; done
((failed == 0)) || { echo "gpu-check: the build failed" >&2; exit "$failed"; }
"$nvcc" -arch=sm_90 "${objects[@]}" -o "$root/build-gpu/grip-gpu-check"
echo "gpu-check: built in $(($(date +%s) - start)) s"
nvidia-smi >"$out/nvidia-smi.txt" 2>&1 || true
status=0
"$root/build-gpu/grip-gpu-check" "$out" "$@" || status=$?
# Then every stage again at 8 environments under compute-sanitizer's memcheck (about 20 s on an
# H200), which names the kernel and the array of an access out of bounds; its errors exit 3.
sanitizer=$(command -v compute-sanitizer || echo "$(dirname "$nvcc")/compute-sanitizer")
if [[ -x $sanitizer ]]; then
  mkdir -p "$out/memcheck"
  timeout 300 "$sanitizer" --tool memcheck --error-exitcode 3 --print-limit 20 \
    "$root/build-gpu/grip-gpu-check" "$out/memcheck" --sizes 8 --repeats 1 \
    >"$out/memcheck.log" 2>&1 || { ((status != 0)) || status=3; }
  echo "gpu-check: memcheck at 8 environments: $(grep -o 'ERROR SUMMARY: [0-9]* error' \
    "$out/memcheck.log" || echo 'no summary'), $out/memcheck.log"
fi
exit "$status"
