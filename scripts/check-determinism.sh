#!/usr/bin/env bash
# Runs the PPO test binaries (rl/tests/ppo.rs, rl/tests/determinism.rs) N times (default 2) on
# the current build, all their tests in parallel threads as `cargo test` runs them, and fails
# unless every run passes and prints the same figures. The seed must decide a training whatever
# else the process does; a figure that moves between runs means some draw is not the run's own.
# Usage: scripts/check-determinism.sh [N]
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-2}"
out="$(mktemp -d "${TMPDIR:-/tmp}/fairgrasp-determinism.XXXXXX")"
trap 'rm -rf "$out"' EXIT
for i in $(seq 1 "$runs"); do
    start=$(date +%s)
    # --workspace, not -p: the same feature set as the suite's build, so nothing is rebuilt.
    if ! cargo test --quiet --locked --workspace --features fairgrasp/train --test ppo --test determinism \
        -- --nocapture >"$out/run$i.log" 2>&1; then
        cat "$out/run$i.log"
        echo "determinism check: run $i of $runs failed" >&2
        exit 1
    fi
    grep -oE 'return per episode.*' "$out/run$i.log" >"$out/figures$i.txt" || true
    if [[ ! -s "$out/figures$i.txt" ]]; then
        echo "determinism check: run $i printed no figures" >&2
        exit 1
    fi
    echo "determinism check: run $i of $runs passed in $(( $(date +%s) - start )) s: $(cat "$out/figures$i.txt")"
    if ! cmp -s "$out/figures1.txt" "$out/figures$i.txt"; then
        echo "determinism check: run $i printed other figures than run 1:" >&2
        diff "$out/figures1.txt" "$out/figures$i.txt" >&2 || true
        exit 1
    fi
done
