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
  python3-h5py python3-matplotlib python3-numpy
  slurm-wlm munge hdf5-tools  # tests/slurm/: a one-node SLURM (scripts/slurm-one-node.sh), h5diff
)
# Optional: grip builds and runs without them; one benchmark each needs them.
optional=(
  libmujoco-dev  # grip bench peer: the same trials in MuJoCo (bench/peer/)
)

missing=() missing_optional=()
for p in "${packages[@]}" "${optional[@]}"; do
  # dpkg-query prints "install ok installed" only for fully installed packages.
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] && continue
  if [[ " ${optional[*]} " == *" $p "* ]]; then missing_optional+=("$p"); else missing+=("$p"); fi
done
[[ ${#missing[@]} -eq 0 && ${#missing_optional[@]} -eq 0 ]] && exit 0

if [[ $(id -u) -eq 0 ]]; then sudo=(); else sudo=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
if [[ ${#missing[@]} -gt 0 ]]; then
  echo "install-deps: installing ${#missing[@]} missing Debian packages: ${missing[*]}" >&2
  "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
if [[ ${#missing_optional[@]} -gt 0 ]]; then
  echo "install-deps: installing optional packages: ${missing_optional[*]}" >&2
  "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing_optional[@]}" >/dev/null ||
    echo "install-deps: optional packages not installed (grip builds without them)" >&2
fi
