#!/usr/bin/env bash
# Checks the wheel scripts/build-wheel.sh made as a user without Rust gets it: installs it into a
# fresh virtual environment with no `cargo` or `rustc` on PATH (pip may take only wheels, so
# nothing can be compiled), then, from a folder outside the repository, makes an env, steps it,
# evaluates a shipped policy and checks `fairgrasp.train` against the wheel's build.
# Usage: scripts/check-wheel.sh [WHEEL]   (default: the one target/wheels/fairgrasp-*.whl)
#   FAIRGRASP_BIN=path/to/fairgrasp (optional, e.g. the test build's target/debug/fairgrasp, a
#   built program, not a toolchain): the shipped policy's episodes must then equal `fairgrasp
#   eval --json`'s one by one.
# Needs python3 with venv and PyPI (numpy and gymnasium, pinned by
# scripts/requirements-python-package.txt). Removes the venv it made.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if [[ $# -gt 1 ]]; then
    echo "usage: scripts/check-wheel.sh [WHEEL]" >&2
    exit 2
fi
if [[ $# -eq 1 ]]; then
    wheel="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
else
    shopt -s nullglob
    found=("$root"/target/wheels/fairgrasp-*.whl)
    if [[ ${#found[@]} -ne 1 ]]; then
        echo "check-wheel: expected one wheel in target/wheels (scripts/build-wheel.sh makes it), found ${#found[@]}: ${found[*]}" >&2
        exit 1
    fi
    wheel="${found[0]}"
fi
[[ -f "$wheel" ]] || { echo "check-wheel: $wheel: no such wheel" >&2; exit 1; }
cli=""
if [[ -n "${FAIRGRASP_BIN:-}" ]]; then
    [[ -x "$FAIRGRASP_BIN" ]] || { echo "check-wheel: FAIRGRASP_BIN=$FAIRGRASP_BIN: no such program" >&2; exit 1; }
    cli="$(cd "$(dirname "$FAIRGRASP_BIN")" && pwd)/$(basename "$FAIRGRASP_BIN")"
fi
[[ "$(basename "$wheel")" == *-abi3-* ]] || { echo "check-wheel: $wheel is not an abi3 wheel" >&2; exit 1; }

# PATH without any folder that holds cargo or rustc (rustup's ~/.cargo/bin, a system Rust).
clean_path=""
IFS=: read -r -a dirs <<<"$PATH"
for dir in "${dirs[@]}"; do
    [[ -n "$dir" && ! -e "$dir/cargo" && ! -e "$dir/rustc" ]] && clean_path="${clean_path:+$clean_path:}$dir"
done
for tool in rm basename python3; do
    if ! PATH="$clean_path" command -v "$tool" >/dev/null 2>&1; then
        echo "check-wheel: without the folders that hold cargo or rustc, PATH has no $tool: Rust is installed beside the system's tools here, so its absence cannot be checked (run where Rust comes from rustup, or on a machine without it)" >&2
        exit 1
    fi
done
python3="$(PATH="$clean_path" command -v python3)"
work="$(mktemp -d "${TMPDIR:-/tmp}/fairgrasp-wheel-check.XXXXXX")"
trap 'rm -rf "$work"' EXIT
export PATH="$clean_path"
unset CARGO CARGO_HOME RUSTUP_HOME RUSTC CARGO_TARGET_DIR VIRTUAL_ENV PYTHONPATH
if command -v cargo >/dev/null 2>&1 || command -v rustc >/dev/null 2>&1; then
    echo "check-wheel: cargo or rustc is still on PATH ($(command -v cargo rustc | tr '\n' ' '))" >&2
    exit 1
fi
echo "check-wheel: no cargo or rustc on PATH; installing $(basename "$wheel") into a fresh venv" >&2
"$python3" -m venv "$work/venv"
# --only-binary: pip installs wheels only (a source build would need the Rust that is not here).
"$work/venv/bin/python" -m pip install --quiet --disable-pip-version-check --only-binary=:all: \
    -c "$root/scripts/requirements-python-package.txt" "$wheel"
cd "$work"
FAIRGRASP_BIN="$cli" FAIRGRASP_WHEEL="$wheel" "$work/venv/bin/python" - <<'PY'
"""The installed wheel, used as a user would: an env made and stepped, a shipped policy evaluated,
fairgrasp.train as the build has it."""
import json
import os
import subprocess
import sys

import gymnasium as gym
import numpy as np

import fairgrasp

venv = os.path.dirname(os.path.dirname(sys.executable))
assert fairgrasp.__file__.startswith(venv), f"fairgrasp imported from {fairgrasp.__file__}, not the venv {venv}"

env = gym.make("FairGrasp-v0", preset="nudged")
obs, info = env.reset(seed=7)
again, _ = gym.make("FairGrasp-v0", preset="nudged").reset(seed=7)
assert obs.shape == (fairgrasp.OBS_DIM,) and np.array_equal(obs, again), "a seeded reset is reproducible"
rng = np.random.default_rng(0)
for step in range(1, 31):
    obs, reward, terminated, truncated, info = env.step(rng.uniform(-1, 1, fairgrasp.ACT_DIM))
    assert np.all(np.isfinite(obs)) and np.isfinite(reward), f"step {step}: non-finite observation or reward"
    if terminated or truncated:
        break
print(f"check-wheel: FairGrasp-v0 on nudged made and stepped {step} times", file=sys.stderr)

policy = fairgrasp.load_policy("residual_nudged")
result = fairgrasp.evaluate(policy, "nudged", episodes=20, seed=7)
assert result["episodes"] == 20 == sum(result["outcomes"].values())
print(f"check-wheel: shipped residual_nudged on nudged, 20 held-out scenarios: {result['successes']}/20 "
      f"(95 % CI {100 * result['ci_low']:.1f}–{100 * result['ci_high']:.1f} %)", file=sys.stderr)
cli = os.environ["FAIRGRASP_BIN"]
if cli:
    rust = json.loads(subprocess.run([cli, "eval", "--policy", "residual_nudged", "--preset", "nudged",
                                      "--episodes", "20", "--seed", "7", "--json"],
                                     check=True, capture_output=True, text=True).stdout)
    for key in ("seed", "outcome", "steps"):
        assert [r[key] for r in result["records"]] == [r[key] for r in rust["results"]], key
    print(f"check-wheel: the same 20 episodes as {cli} eval --json", file=sys.stderr)

extension = os.path.join(os.path.dirname(fairgrasp.__file__), [f for f in os.listdir(os.path.dirname(fairgrasp.__file__)) if f.startswith("_native")][0])
with open(extension, "rb") as f:
    has_burn = b"burn_core" in f.read()
if fairgrasp._native.HAS_TRAIN:
    print("check-wheel: this wheel has the trainer (built with --features train)", file=sys.stderr)
else:
    assert not has_burn, f"{extension}: built without the trainer, yet it holds burn's code"
    try:
        fairgrasp.train("residual_miscalibrated", "never-written")
    except RuntimeError as e:
        assert '--config-settings=build-args="--features train"' in str(e), e
    else:
        raise AssertionError("fairgrasp.train ran without the trainer")
    assert not os.path.exists("never-written")
    print("check-wheel: no trainer and no burn inside; fairgrasp.train says how to get it", file=sys.stderr)
print(f"check-wheel: OK ({os.path.basename(os.environ['FAIRGRASP_WHEEL'])})")
PY
