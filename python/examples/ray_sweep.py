"""A sweep of Rust PPO trainings as Ray tasks (Ray core; no torch): each task runs
`fairgrasp.train` (the Rust trainer, in the worker's process, GIL released) into its own run
folder and returns the run's final evaluation, so the results come back to this script as
values, and the run folders stay where the tasks ran.

One machine, two workers (what was tried here):

    pip install "ray==2.60.0"        # beside fairgrasp
    python python/examples/ray_sweep.py --workers 2 --seeds 0 1 --timesteps 20000

A cluster: start Ray on every node with fairgrasp installed there (`ray start --head` on one,
`ray start --address=HEAD:6379` on the others), then run the same script on the head with
`--address auto` and `--runs-root` a folder every node can write (a shared file system), or a
local one (each run folder then stays on the node that trained it; the returned evaluation is
what comes back). Each task asks for `--threads` CPUs, so Ray places as many trainings per node as
it has cores for.
"""

import argparse
import os
import time

import ray

parser = argparse.ArgumentParser()
parser.add_argument("--config", default="residual_miscalibrated", help="a shipped recipe or a training config's path")
parser.add_argument("--preset", default="nudged")
parser.add_argument("--seeds", type=int, nargs="+", default=[0, 1])
parser.add_argument("--timesteps", type=int, default=300_000)
parser.add_argument("--threads", type=int, default=1, help="CPUs per training (its env threads)")
parser.add_argument("--workers", type=int, default=2, help="CPUs of the local Ray instance (without --address)")
parser.add_argument("--address", default=None, help="an existing Ray cluster (e.g. auto)")
parser.add_argument("--runs-root", default=os.path.abspath("runs/ray_sweep"))
args = parser.parse_args()

if args.address:
    ray.init(address=args.address)
else:
    ray.init(num_cpus=args.workers, include_dashboard=False)


@ray.remote
def train_one(config, run_dir, overrides):
    import socket

    import fairgrasp

    start = time.time()
    report = fairgrasp.train(config, run_dir, **overrides)
    return {
        "run_dir": run_dir,
        "node": socket.gethostname(),
        "pid": os.getpid(),
        "wall_s": round(time.time() - start, 1),
        "success_rate": report["success_rate"],
        "episodes": report["episodes"],
        "ci95": (report["ci_low"], report["ci_high"]),
    }


tasks = [
    train_one.options(num_cpus=args.threads).remote(
        args.config,
        os.path.join(args.runs_root, f"{args.preset}_seed{seed}"),
        dict(preset=args.preset, seed=seed, total_timesteps=args.timesteps, threads=args.threads),
    )
    for seed in args.seeds
]
start = time.time()
for result in ray.get(tasks):
    print(result)
print(f"{len(tasks)} trainings in {time.time() - start:.0f} s of wall time")
