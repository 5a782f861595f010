#!/usr/bin/env bash
# The six-axis wrist sensor's cost per env step (docs/place.md, "The six-axis wrist sensor"):
# alternating runs of the force search on place_cell by two release builds, BEFORE_BIN (without the
# sensor, f367bbf) and AFTER_BIN, each printing env steps per CPU-second (user + sys).
# Usage: scripts/bench-wrench-sensor.sh BEFORE_BIN AFTER_BIN [RUNS]
set -euo pipefail
before="$1" after="$2" runs="${3:-3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for _ in $(seq "$runs"); do
    for bin in "$before" "$after"; do
        /usr/bin/time -f "%U %S" -o "$work/time" "$bin" baseline --preset place_cell \
            --script force_search --episodes 100 --seed 11 --threads 1 --json >"$work/out.json" 2>/dev/null
        python3 - "$bin" "$work/out.json" "$work/time" <<'PY'
import json, sys
steps = sum(r["steps"] for r in json.load(open(sys.argv[2]))["results"])
cpu = sum(float(x) for x in open(sys.argv[3]).read().split())
print(f"{sys.argv[1]}: {steps} env steps in {cpu:.2f} CPU-s, {steps / cpu:.0f} steps/CPU-s")
PY
    done
done
