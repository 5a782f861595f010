"""Ray RLlib PPO on FairGrasp (needs `pip install "ray[rllib]==2.60.0" torch`).

One machine: `python python/examples/rllib_ppo.py --runners 2`. On a Ray cluster, start the head
and workers (`ray start --head`, `ray start --address=HEAD:6379`, with fairgrasp installed on
every node), then run the same script with `--address auto` and more `--runners`: RLlib ships
the env by pickling its constructor arguments (FairGraspEnv is an EzPickle) to each runner.
"""

import argparse

import ray
from ray.rllib.algorithms.ppo import PPOConfig
from ray.tune.registry import register_env

import fairgrasp

parser = argparse.ArgumentParser()
parser.add_argument("--preset", default="seed")
parser.add_argument("--runners", type=int, default=2)
parser.add_argument("--iterations", type=int, default=20)
parser.add_argument("--address", default=None)
args = parser.parse_args()

ray.init(address=args.address)
register_env("fairgrasp", lambda cfg: fairgrasp.FairGraspEnv(**cfg))
config = (
    PPOConfig()
    .environment("fairgrasp", env_config={"preset": args.preset})
    .env_runners(num_env_runners=args.runners, num_envs_per_env_runner=4)
    .training(gamma=0.95, lambda_=0.9, lr=3e-4)
)
algo = config.build_algo()
for i in range(args.iterations):
    result = algo.train()
    print(i, result["env_runners"]["episode_return_mean"])
