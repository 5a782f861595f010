#!/usr/bin/env bash
# Does skipping physics in free space change what the baseline achieves? For every preset, the
# scripted baseline on the same scenarios with `physics.free_space` on (the default) and off:
# success rates with 95 % Wilson intervals, and the paired outcome table with an exact McNemar
# test on the episodes whose success differs.
# Usage: scripts/free_space_equivalence.sh PATH/TO/fairgrasp [EPISODES=200] [SEED=0]
set -euo pipefail
bin=${1:?usage: free_space_equivalence.sh PATH/TO/fairgrasp [EPISODES] [SEED]}
episodes=${2:-200}
seed=${3:-0}
here=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for preset in fixed sector wide full hard; do
  "$bin" baseline --preset "$preset" --episodes "$episodes" --seed "$seed" --json \
    >"$tmp/$preset.on.json"
  { cat "$here/assets/configs/$preset.toml"; printf '\n[physics]\nfree_space = false\n'; } \
    >"$tmp/$preset.off.toml"
  "$bin" baseline --preset "$tmp/$preset.off.toml" --episodes "$episodes" --seed "$seed" --json \
    >"$tmp/$preset.off.json"
done
python3 - "$tmp" <<'PY'
import json, math, sys
tmp = sys.argv[1]

def wilson(k, n, z=1.959964):
    p = k / n
    d = 1 + z * z / n
    c = (p + z * z / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return c - h, c + h

def mcnemar_exact(b, c):
    n = b + c
    if n == 0:
        return 1.0
    tail = sum(math.comb(n, i) for i in range(0, min(b, c) + 1)) / 2 ** n
    return min(1.0, 2 * tail)

print("| preset | free space on | off (always simulate) | same outcome | on only / off only | McNemar p |")
print("|---|---|---|---|---|---|")
for preset in ["fixed", "sector", "wide", "full", "hard"]:
    on = json.load(open(f"{tmp}/{preset}.on.json"))["results"]
    off = json.load(open(f"{tmp}/{preset}.off.json"))["results"]
    assert [r["seed"] for r in on] == [r["seed"] for r in off]
    n = len(on)
    def cell(rs):
        k = sum(r["outcome"] == "success" for r in rs)
        lo, hi = wilson(k, n)
        return f"{100 * k / n:.1f} % [{100 * lo:.1f}, {100 * hi:.1f}]"
    same = sum(a["outcome"] == b["outcome"] for a, b in zip(on, off))
    b = sum(a["outcome"] == "success" and o["outcome"] != "success" for a, o in zip(on, off))
    c = sum(a["outcome"] != "success" and o["outcome"] == "success" for a, o in zip(on, off))
    print(f"| {preset} | {cell(on)} | {cell(off)} | {same}/{n} | {b} / {c} | {mcnemar_exact(b, c):.3f} |")
PY
