#!/usr/bin/env bash
# The env's speed on the scripted baseline's own episodes (approach, close, lift: the contact-
# rich workload), side by side with the PyBullet seed-recipe env (../shared/peers), in one run:
# env steps per CPU-second, single thread, alternating ours and the peer's 3 times.
# Usage: scripts/env_ratio_scripted.sh [PRESET] [EPISODES]   (default full 100)
# Builds the release example `scripted_episodes` (planner/examples/) first; the peer's venv is
# the one ../shared/peers/env_ratio.sh creates (${FAIRGRASP_PEER_VENV:-~/.cache/fairgrasp-peer-venv}).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
preset=${1:-full}; episodes=${2:-100}
peer_dir="$root/../shared/peers/pybullet_seed_env"
venv=${FAIRGRASP_PEER_VENV:-$HOME/.cache/fairgrasp-peer-venv}
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c "import pybullet, gymnasium" 2>/dev/null; then
  python3 -m venv "$venv" >&2
  "$venv/bin/pip" install -q pybullet==3.2.7 gymnasium==1.4.0 numpy >&2
fi
cargo build --quiet --release --locked -p fairgrasp-planner --example scripted_episodes
bin="$root/target/release/examples/scripted_episodes"
ours=(); peer=()
for _ in 1 2 3; do
  o=$("$bin" "$preset" "$episodes" | sed -n 's/^STEPS_PER_CPU_S=//p')
  q=$(cd "$peer_dir" && "$venv/bin/python" rate.py 1000 2>/dev/null | sed -n 's/^PEER_RATE=//p')
  ours+=("$o"); peer+=("$q")
done
python3 - "$preset" "${ours[@]}" "${peer[@]}" <<'PY'
import statistics, sys
preset, v = sys.argv[1], [float(x) for x in sys.argv[2:]]
ours, peer = v[:3], v[3:]
ratios = [o / p for o, p in zip(ours, peer)]
print(f"scripted episodes on {preset}, fairgrasp env steps / CPU-s:", " ".join(f"{x:.0f}" for x in ours))
print("PyBullet seed env steps / CPU-s:", " ".join(f"{x:.0f}" for x in peer))
print(f"ratio per run: {' '.join(f'{r:.2f}' for r in ratios)}; median {statistics.median(ratios):.2f}")
PY
