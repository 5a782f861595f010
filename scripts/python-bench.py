"""Python-side env steps per second of fairgrasp (one env, and the native vector env on 2
threads) beside the PyBullet seed-recipe env (../shared/peers/pybullet_seed_env), measured in one
run, alternating, 3 times each; random actions, the `seed` preset (position and yaw randomised).

    target/python-package-venv/bin/python scripts/python-bench.py [STEPS]

The peer runs in its own venv (created by ../shared/peers/env_ratio.sh, or here on first use).
Prints one line per measurement and the medians; a benchmark, never a test.
"""

import os
import statistics
import subprocess
import sys
import time

import numpy as np

import fairgrasp

steps = int(sys.argv[1]) if len(sys.argv) > 1 else 5000
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
peer_dir = os.path.join(root, "..", "shared", "peers", "pybullet_seed_env")
peer_venv = os.environ.get("FAIRGRASP_PEER_VENV", os.path.expanduser("~/.cache/fairgrasp-peer-venv"))
peer_python = os.path.join(peer_venv, "bin", "python")
if not os.path.exists(peer_python):
    subprocess.run([sys.executable, "-m", "venv", peer_venv], check=True)
    subprocess.run([peer_python, "-m", "pip", "install", "-q", "pybullet==3.2.7", "gymnasium==1.4.0", "numpy"], check=True)


def single():
    env = fairgrasp.FairGraspEnv(preset="seed")
    env.reset(seed=0)
    actions = np.random.default_rng(0).uniform(-1, 1, (steps, 7))
    w0, c0 = time.perf_counter(), time.process_time()
    for a in actions:
        _, _, te, tr, _ = env.step(a)
        if te or tr:
            env.reset()
    return steps / (time.perf_counter() - w0), steps / (time.process_time() - c0)


def vector(n=8):
    env = fairgrasp.VectorEnv(num_envs=n, preset="seed", threads=2, seed=0)
    env.reset()
    batches = steps // n
    actions = np.random.default_rng(0).uniform(-1, 1, (batches, n, 7))
    w0, c0 = time.perf_counter(), time.process_time()
    for a in actions:
        env.step(a)
    return batches * n / (time.perf_counter() - w0), batches * n / (time.process_time() - c0)


def peer():
    out = subprocess.run([peer_python, "rate.py", str(min(steps, 2000))], cwd=peer_dir, capture_output=True, text=True, check=True)
    return float(out.stdout.split("PEER_RATE=")[1])


rows = {"fairgrasp, 1 env (wall)": [], "fairgrasp, 1 env (CPU)": [], "fairgrasp vector, 8 envs / 2 threads (wall)": [], "fairgrasp vector (CPU, both threads)": [], "PyBullet seed env (CPU)": []}
for _ in range(3):
    w, c = single()
    rows["fairgrasp, 1 env (wall)"].append(w)
    rows["fairgrasp, 1 env (CPU)"].append(c)
    w, c = vector()
    rows["fairgrasp vector, 8 envs / 2 threads (wall)"].append(w)
    rows["fairgrasp vector (CPU, both threads)"].append(c)
    rows["PyBullet seed env (CPU)"].append(peer())
for name, values in rows.items():
    print(f"{name:45s} " + " ".join(f"{v:9.0f}" for v in values) + f"   median {statistics.median(values):9.0f} steps/s")
ratio = statistics.median(rows["fairgrasp, 1 env (CPU)"]) / statistics.median(rows["PyBullet seed env (CPU)"])
print(f"one env from Python per CPU-second vs the PyBullet seed env: {ratio:.2f}x")
