#!/usr/bin/env bash
# Installs the optional peers of grip's physics from PyPI into a virtual environment (Debian's
# Python refuses system-wide pip installs): MuJoCo (its libmujoco and headers, which
# `grip bench peer` links; flex FEM for the fin-ray) and ipc-toolkit (`ipctk`, the IPC authors'
# reference kernels, the oracle of tests/oracle/). Versions are pinned so results reproduce.
# Idempotent: returns at once when the pinned versions are present. Without network it says so
# and exits 0: grip builds without them, the peer benchmark says what to install and the oracle
# test reports itself not run.
# Usage: scripts/install-peers.sh [VENV]   (default: .peers-venv in the repository root)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
venv=${1:-${GRIP_PEERS_VENV:-$root/.peers-venv}}
pins=(mujoco==4.0.0 ipctk==1.6.1 numpy==2.4.6)
stamp="$venv/.grip-peers"
[[ -f "$stamp" && "$(cat "$stamp")" == "${pins[*]}" ]] && exit 0
if ! /usr/bin/python3 -m venv "$venv" >/dev/null 2>&1; then
  echo "install-peers: /usr/bin/python3 -m venv failed (apt-get install python3-venv);" \
    "MuJoCo and ipc-toolkit not installed" >&2
  exit 0
fi
echo "install-peers: installing ${pins[*]} into $venv" >&2
if "$venv/bin/pip" install --quiet --disable-pip-version-check "${pins[@]}"; then
  echo "${pins[*]}" >"$stamp"
else
  echo "install-peers: pip could not install ${pins[*]} (no network?); grip builds without" \
    "them" >&2
fi
