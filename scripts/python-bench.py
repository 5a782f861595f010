"""The Python layer's cost, measured side by side in one run (a benchmark, never a test): one
`FairGraspEnv` stepped from Python against the same steps of the Rust `TaskEnv` in a Rust loop
(same process, same build, same actions and seeds), and the native vector env's throughput
against one env's. Random actions on `sector` from the home pose, so almost every step is a
free-space step (the share that ran physics is printed); then the open-loop script's own
episodes (the residual recipe's env with zero corrections: approach, close, lift), one env and
8 envs on 2 threads. Each measurement runs ROUNDS times,
alternating, and the ratios are taken within a round (the machine may be shared).

    target/python-package-venv/bin/python scripts/python-bench.py [STEPS] [ROUNDS]

With FAIRGRASP_BENCH_PEER=1 it also times the PyBullet seed env (../shared/peers/pybullet_seed_env,
in its own venv, created on first use) per CPU-second.
"""

import os
import statistics
import subprocess
import sys
import time

import numpy as np

import fairgrasp
from fairgrasp import _native

steps = int(sys.argv[1]) if len(sys.argv) > 1 else 20000
rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 5
actions = np.random.default_rng(0).uniform(-1, 1, (steps, 7))


def rust_single():
    wall, simulated = _native.bench_rust_env("sector", actions, 0)
    return steps / wall, simulated


def python_single():
    env = fairgrasp.FairGraspEnv(preset="sector")
    seed = 0
    env.reset(seed=seed)
    w0 = time.perf_counter()
    for a in actions:
        _, _, te, tr, _ = env.step(a)
        if te or tr:
            seed += 1
            env.reset(seed=seed)
    return steps / (time.perf_counter() - w0)


def python_vector(n, threads):
    env = fairgrasp.VectorEnv(num_envs=n, preset="sector", threads=threads, seed=0)
    env.reset()
    batch = actions[: (steps // n) * n].reshape(-1, n, 7)
    w0 = time.perf_counter()
    for a in batch:
        env.step(a)
    return batch.shape[0] * n / (time.perf_counter() - w0)


def scripted_single(n_steps):
    """The open-loop script's own episodes (approach, close, lift: contact-rich steps): the
    residual recipe's env on `sector` with zero corrections, one env from Python."""
    env = fairgrasp.make("residual_miscalibrated", preset="sector", evaluation=True)
    zero = np.zeros(7)
    seed = 0
    env.reset(seed=seed)
    w0 = time.perf_counter()
    for _ in range(n_steps):
        _, _, te, tr, _ = env.step(zero)
        if te or tr:
            seed += 1
            env.reset(seed=seed)
    return n_steps / (time.perf_counter() - w0)


def scripted_vector(n, threads, n_steps):
    """The same episodes, `n` envs of the native vector env on `threads` threads."""
    env = fairgrasp.make_vec("residual_miscalibrated", num_envs=n, threads=threads, preset="sector",
                             evaluation=True)
    env.reset()
    zero = np.zeros((n, 7))
    calls = n_steps // n
    w0 = time.perf_counter()
    for _ in range(calls):
        env.step(zero)
    return calls * n / (time.perf_counter() - w0)


def rust_vector(n, threads):
    batch = actions[: (steps // n) * n].reshape(-1, n, 7)
    return batch.shape[0] * n / _native.bench_rust_vec("sector", threads, batch, 0)


def peer():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    peer_dir = os.path.join(root, "..", "shared", "peers", "pybullet_seed_env")
    venv = os.environ.get("FAIRGRASP_PEER_VENV", os.path.expanduser("~/.cache/fairgrasp-peer-venv"))
    python = os.path.join(venv, "bin", "python")
    if not os.path.exists(python):
        subprocess.run([sys.executable, "-m", "venv", venv], check=True)
        subprocess.run([python, "-m", "pip", "install", "-q", "pybullet==3.2.7", "gymnasium==1.4.0", "numpy"], check=True)
    out = subprocess.run([python, "rate.py", str(min(steps, 2000))], cwd=peer_dir, capture_output=True, text=True, check=True)
    return float(out.stdout.split("PEER_RATE=")[1])


rows = {}


def add(name, value):
    rows.setdefault(name, []).append(value)


for r in range(rounds):
    rust, simulated = rust_single()
    py = python_single()
    add("Rust TaskEnv, Rust loop", rust)
    add("FairGraspEnv from Python", py)
    add("  ratio: Python per-step cost / Rust's", rust / py)
    add("  share of steps that ran physics [%]", 100 * simulated)
    v8 = python_vector(8, 2)
    add("VectorEnv, 8 envs / 2 threads, from Python", v8)
    add("  ratio: 8 envs on 2 threads / one env", v8 / py)
    add("VectorEnv, 8 envs / 1 thread, from Python", python_vector(8, 1))
    add("  ratio: 2 threads / 1 thread (8 envs)", v8 / rows["VectorEnv, 8 envs / 1 thread, from Python"][-1])
    add("Rust VecEnv, 8 envs / 2 threads, Rust loop", rust_vector(8, 2))
    scripted_steps = max(steps // 5, 400)
    s1 = scripted_single(scripted_steps)
    add("script's episodes, one env, from Python", s1)
    s8 = scripted_vector(8, 2, scripted_steps)
    add("script's episodes, 8 envs / 2 threads", s8)
    add("  ratio: script's episodes, 8 envs on 2 threads / one env", s8 / s1)
    if os.environ.get("FAIRGRASP_BENCH_PEER"):
        add("PyBullet seed env (per CPU-second)", peer())
    print(f"round {r + 1}/{rounds} done", file=sys.stderr)

print(f"{steps} steps per measurement, {rounds} rounds, os.cpu_count() = {os.cpu_count()}, "
      f"load average before the last round {os.getloadavg()[0]:.1f}")
for name, values in rows.items():
    fmt = (lambda v: f"{v:9.2f}") if "ratio" in name or "share" in name else (lambda v: f"{v:9.0f}")
    unit = "" if "ratio" in name or "share" in name else " steps/s"
    print(f"{name:48s} " + " ".join(fmt(v) for v in values) + f"   median {fmt(statistics.median(values)).strip()}{unit}")
