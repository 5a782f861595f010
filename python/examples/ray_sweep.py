"""A sweep of Rust PPO trainings on Ray Tune (``fairgrasp.tune``, tested by python/tests-ray):
seeds × a grid of recipe overrides, ASHA stopping the trials whose held-out evaluation success
falls behind, every trial's run folder (metrics.csv, TensorBoard events, checkpoints) kept under
``--out``, the table printed and written to ``--out``/sweep.md and sweep.json.

One machine, two trials at a time (one thread each):

    pip install "ray[tune]==2.60.0"        # beside fairgrasp (scripts/requirements-ray.txt)
    cargo build --release --features train
    FAIRGRASP_BIN=target/release/fairgrasp python python/examples/ray_sweep.py --cpus 2 \\
        --seeds 0 1 --learning-rates 3e-4 1e-3 --timesteps 100000 --out runs/ray_sweep

The same as ``python -m fairgrasp.tune residual_miscalibrated --out runs/ray_sweep --cpus 2
--seeds 0 1 --grid ppo.learning_rate=3e-4,1e-3 --set preset=nudged --set total_timesteps=100000
--set threads=1``.

A cluster: start Ray on every node with the binary at the same path there (``ray start --head``
on one, ``ray start --address=HEAD:6379`` on the others), then run this script on the head with
``--address auto`` and ``--out`` a folder every node can write (a shared file system): each trial
writes its run folder where it runs.
"""

import argparse

import fairgrasp.tune

parser = argparse.ArgumentParser()
parser.add_argument("--recipe", default="residual_miscalibrated", help="a shipped recipe or a training config's path")
parser.add_argument("--preset", default="nudged")
parser.add_argument("--seeds", type=int, nargs="+", default=[0, 1])
parser.add_argument("--learning-rates", type=float, nargs="+", default=[3e-4, 1e-3])
parser.add_argument("--timesteps", type=int, default=100_000)
parser.add_argument("--threads", type=int, default=1, help="env threads (and CPUs) per training")
parser.add_argument("--cpus", type=int, default=2, help="CPUs of the local Ray instance (without --address)")
parser.add_argument("--address", default=None, help="an existing Ray cluster (e.g. auto)")
parser.add_argument("--out", default="runs/ray_sweep")
parser.add_argument("--force", action="store_true", help="move an earlier --out aside")
args = parser.parse_args()

table = fairgrasp.tune.sweep(
    args.recipe, args.out, seeds=args.seeds, grid={"ppo.learning_rate": args.learning_rates},
    fixed={"preset": args.preset, "total_timesteps": args.timesteps, "threads": args.threads},
    num_cpus=args.cpus, address=args.address, force=args.force,
)
print(fairgrasp.tune.format_table(table), end="")
