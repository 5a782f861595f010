#!/usr/bin/env bash
# The grid search that tunes the force-guided search's parameters on training scenarios (seed
# 11, never a reported one), as an integrator would: every combination of touch force, spiral
# pitch and spiral speed on PRESET (default place_fixture_error), EPISODES each (default 100).
# With BANDS (e.g. "0.001 0.002 0.003"), also every floor band (`--search-floor-band`: how near
# the floor a touch must be to count as the cube in); without, the preset's own.
# Prints one line per point, best last; docs/place.md records the result.
# Usage: scripts/tune-force-search.sh [PRESET] [EPISODES] [BANDS]   (after cargo build --release)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-place_fixture_error}"
episodes="${2:-100}"
bands="${3:-preset}"
bin=target/release/fairgrasp
for band in $bands; do
    band_flag=()
    [ "$band" = preset ] || band_flag=(--search-floor-band "$band")
    for force in 1.0 1.5 3.0; do
        for pitch in 0.002 0.003 0.004; do
            for speed in 0.01 0.015 0.025; do
                rate=$("$bin" baseline --preset "$preset" --script force_search --seed 11 \
                    --episodes "$episodes" --search-force "$force" --search-pitch "$pitch" \
                    --search-speed "$speed" "${band_flag[@]}" --json |
                    python3 -c 'import json,sys; d=json.load(sys.stdin); print(d["successes"], d["mean_steps_to_success"])')
                echo "band $band force $force pitch $pitch speed $speed: $rate"
            done
        done
    done
done | sort -t: -k2 -n
