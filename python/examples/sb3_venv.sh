#!/usr/bin/env bash
# Creates the venv the SB3 examples run in (torch + Stable-Baselines3 + fairgrasp) and stages the
# fairgrasp package into it; kept out of CI (torch from PyPI brings its CUDA libraries: several
# GB). Run it again after rebuilding the extension: only the staging is redone.
# Usage: python/examples/sb3_venv.sh [VENV]   (default: target/sb3-venv)
#   The package is staged (scripts/stage-package.sh) from python/ with the extension `cargo test
#   --workspace` builds (target/debug/deps/lib_native.so) when it exists, else built by maturin.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
venv="${1:-$root/target/sb3-venv}"
if ! [[ -x "$venv/bin/python" ]] || ! "$venv/bin/python" -c "import torch, stable_baselines3" 2>/dev/null; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet --disable-pip-version-check \
        "torch==2.15.0" "stable-baselines3==2.9.2" "maturin==1.16.0" "tomli==2.4.1; python_version < '3.11'"
fi
lib="$root/target/debug/deps/lib_native.so"
[[ -f "$lib" ]] || lib=""
"$root/scripts/stage-package.sh" "$venv" "$lib"
echo "venv ready: $venv/bin/python"
