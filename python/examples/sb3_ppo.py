"""Stable-Baselines3 PPO on FairGrasp (needs `pip install stable-baselines3`, which brings torch).

    python python/examples/sb3_ppo.py --preset sector --timesteps 200000
"""

import argparse

from stable_baselines3 import PPO

from fairgrasp.sb3 import FairGraspVecEnv

parser = argparse.ArgumentParser()
parser.add_argument("--preset", default="sector")
parser.add_argument("--timesteps", type=int, default=200_000)
parser.add_argument("--envs", type=int, default=8)
args = parser.parse_args()

env = FairGraspVecEnv(args.envs, preset=args.preset, threads=2, seed=0)
model = PPO("MlpPolicy", env, n_steps=256, batch_size=256, seed=0, verbose=1)
model.learn(total_timesteps=args.timesteps)
model.save(f"ppo_fairgrasp_{args.preset}")
