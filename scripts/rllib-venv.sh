#!/usr/bin/env bash
# Creates the venv RLlib's PPO runs in (python/examples/rllib_ppo.py): torch, Ray RLlib 2.60.0 and
# Stable-Baselines3 side by side (so RLlib's throughput is measured against SB3's with the same
# torch in the same venv), and stages the fairgrasp package into it. Kept out of CI (torch from
# PyPI brings its CUDA libraries: several GB). Run it again after rebuilding the extension: only
# the staging is redone.
# Usage: scripts/rllib-venv.sh [VENV]   (default: target/rllib-venv)
#   The package is staged (scripts/stage-package.sh) from python/ with the extension `cargo test
#   --workspace` builds (target/debug/deps/lib_native.so) when it exists, else built by maturin.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
venv="${1:-$root/target/rllib-venv}"
if ! [[ -x "$venv/bin/python" ]] || ! "$venv/bin/python" -c "import torch, stable_baselines3, ray.rllib" 2>/dev/null; then
    python3 -m venv "$venv"
    # gymnasium 1.2.2: what RLlib 2.60 pins (the package's tests use the same).
    "$venv/bin/pip" install --quiet --disable-pip-version-check \
        "torch==2.15.0" "ray[rllib]==2.60.0" "stable-baselines3==2.9.2" "gymnasium==1.2.2" \
        "maturin==1.16.0" "tomli==2.4.1; python_version < '3.11'"
fi
lib="$root/target/debug/deps/lib_native.so"
[[ -f "$lib" ]] || lib=""
"$root/scripts/stage-package.sh" "$venv" "$lib"
echo "venv ready: $venv/bin/python"
