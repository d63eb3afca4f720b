#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and runs the most complete job
# grip can do today (see README.md).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/build.sh"
grip="$root/build/grip"
"$grip" --version
