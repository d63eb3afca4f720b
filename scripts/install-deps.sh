#!/usr/bin/env bash
# Installs grip's build and run dependencies from Debian 12 packages.
# Idempotent: when every package is already present it returns in well under a second.
# Works as root or through sudo.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libopenmpi-dev openmpi-bin
  libhdf5-openmpi-dev libssl-dev zlib1g-dev
  libpetsc-real-dev libmetis-dev
  libcgal-dev libgmp-dev libmpfr-dev
  libsuitesparse-dev libopenblas0-pthread
  libeigen3-dev libspdlog-dev libfmt-dev libtbb-dev
  libtomlplusplus-dev libcli11-dev liburdfdom-dev clang-format nlohmann-json3-dev
  clang-14 libclang-rt-14-dev  # scripts/fuzz.sh: clang and its libFuzzer runtime
  libgtest-dev libgmock-dev libbenchmark-dev
  python3-h5py python3-matplotlib python3-numpy python3-venv
  python3-torch  # examples/stress_prediction/ (CPU PyTorch 1.13)
  slurm-wlm munge hdf5-tools  # tests/slurm/: a one-node SLURM (scripts/slurm-one-node.sh), h5diff
)
# The optional peers MuJoCo and ipc-toolkit come from PyPI (scripts/install-peers.sh).

missing=()
for p in "${packages[@]}"; do
  # dpkg-query prints "install ok installed" only for fully installed packages.
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] && continue
  missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

if [[ $(id -u) -eq 0 ]]; then sudo=(); else sudo=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
echo "install-deps: installing ${#missing[@]} missing Debian packages: ${missing[*]}" >&2
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
