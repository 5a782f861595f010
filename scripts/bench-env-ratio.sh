#!/usr/bin/env bash
# Issue 61's side-by-side measurement of the env on real grasps: the scripted baseline's own
# episodes (`fairgrasp baseline --preset PRESET --episodes N --threads 1 --json`, its env steps
# counted from the JSON, its CPU time — user + system — from the kernel through /usr/bin/time)
# against the PyBullet seed-recipe env (../shared/peers/pybullet_seed_env/rate.py: random
# actions, its own CPU clock, the median of 3 × PEER_STEPS steps), alternating RUNS times in one
# run; then ../shared/peers/env_ratio.sh (random actions, the free-space step) on the same binary.
# Run it on an idle machine: the figures are CPU time, and a busy machine inflates both sides
# unevenly.
#
# Usage: scripts/bench-env-ratio.sh [BIN] [EPISODES] [RUNS] [PEER_STEPS] [PRESET]
#   defaults: target/release/fairgrasp (built with `cargo build --release --locked -p fairgrasp`
#   when absent), 200, 3, 1000, sector. Prints each run's env steps per CPU-second on both sides
#   and their ratio, the median ratio, then env_ratio.sh's lines.
# The peer's venv (pybullet, gymnasium, numpy: scripts/requirements-peer.txt) is made once by
# scripts/python-env.sh in ${FAIRGRASP_PEER_VENV:-~/.cache/fairgrasp-peer-venv}, the venv
# env_ratio.sh uses.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/target/release/fairgrasp}
episodes=${2:-200}
runs=${3:-3}
peer_steps=${4:-1000}
preset=${5:-sector}
peers="$root/../shared/peers"
[[ -f "$peers/pybullet_seed_env/rate.py" ]] || { echo "no $peers/pybullet_seed_env/rate.py" >&2; exit 1; }
if [[ ! -x "$bin" ]]; then
    if [[ "$bin" != "$root/target/release/fairgrasp" ]]; then
        echo "no executable $bin" >&2
        exit 1
    fi
    (cd "$root" && cargo build --release --locked -p fairgrasp)
fi
bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
python=$("$root/scripts/python-env.sh" "${FAIRGRASP_PEER_VENV:-$HOME/.cache/fairgrasp-peer-venv}" \
    "$root/scripts/requirements-peer.txt")
work=$(mktemp -d "${TMPDIR:-/tmp}/fairgrasp-bench-env.XXXXXX")
trap 'rm -rf "$work"' EXIT

ours=(); peer=()
for i in $(seq 1 "$runs"); do
    /usr/bin/time -f "%U %S" -o "$work/time$i" \
        "$bin" baseline --preset "$preset" --episodes "$episodes" --threads 1 --json >"$work/run$i.json"
    o=$(python3 - "$work/run$i.json" "$work/time$i" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
steps = sum(r["steps"] for r in report["results"])
user, system = (float(x) for x in open(sys.argv[2]).read().split()[-2:])
cpu = max(user + system, 0.01)  # /usr/bin/time's resolution: 10 ms
print(f"{steps / cpu:.1f}")
print(f"fairgrasp baseline: {report['episodes']} episodes, {report['successes']} successes, "
      f"{steps} env steps in {user:.2f} s user + {system:.2f} s system CPU", file=sys.stderr)
PY
)
    q=$(cd "$peers/pybullet_seed_env" && "$python" rate.py "$peer_steps" 2>/dev/null | sed -n 's/^PEER_RATE=//p')
    [[ -n "$q" ]] || { echo "rate.py printed no PEER_RATE" >&2; exit 1; }
    ours+=("$o"); peer+=("$q")
done
python3 - "$preset" "$episodes" "${ours[@]}" "${peer[@]}" <<'PY'
import statistics, sys
preset, episodes, v = sys.argv[1], sys.argv[2], [float(x) for x in sys.argv[3:]]
n = len(v) // 2
ours, peer = v[:n], v[n:]
ratios = [o / p for o, p in zip(ours, peer)]
print(f"scripted baseline on {preset}, {episodes} episodes, 1 thread: fairgrasp env steps / CPU-s:",
      " ".join(f"{x:.0f}" for x in ours))
print("PyBullet seed env (rate.py) env steps / CPU-s:", " ".join(f"{x:.0f}" for x in peer))
print(f"ratio per run: {' '.join(f'{r:.2f}' for r in ratios)}; median {statistics.median(ratios):.2f} (target >= 10)")
PY
echo "random actions (../shared/peers/env_ratio.sh):"
FAIRGRASP_PEER_VENV=${FAIRGRASP_PEER_VENV:-$HOME/.cache/fairgrasp-peer-venv} "$peers/env_ratio.sh" "$bin"
