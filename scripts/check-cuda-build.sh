#!/usr/bin/env bash
# CI's check that the CUDA sources are compiled on every landing: each .cu file of the tree is a
# source of a CMake target, and where nvcc is at hand the build in build/ made grip-gpu-check
# (GRIP_CUDA, docs/architecture.md "Build, tests, CI"), with nvcc's warnings as errors.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
status=0
while IFS= read -r source; do
  dir=$(dirname "$source")
  name=${source#"$dir"/}
  found=0
  # The CMakeLists.txt of its folder or of a folder above names it by its path from there.
  while [[ $dir != . ]]; do
    [[ -f $dir/CMakeLists.txt ]] && grep -qF "$name" "$dir/CMakeLists.txt" && { found=1; break; }
    name=$(basename "$dir")/$name
    dir=$(dirname "$dir")
  done
  [[ $found == 1 ]] || { echo "check-cuda-build: $source is in no CMake target" >&2; status=1; }
done < <(git ls-files '*.cu')
if command -v nvcc >/dev/null || [[ -x /usr/local/cuda/bin/nvcc ]]; then
  [[ -x build/grip-gpu-check ]] ||
    { echo "check-cuda-build: nvcc is here but build/grip-gpu-check was not built" >&2; status=1; }
fi
[[ $status == 0 ]] && echo "check-cuda-build: $(git ls-files '*.cu' | wc -l) CUDA source(s) built"
exit $status
