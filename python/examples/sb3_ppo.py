"""Stable-Baselines3 PPO on FairGrasp (needs `pip install stable-baselines3`, which brings torch):
the preset's plain env (lift or place), the model saved, then evaluated on `--episodes`
held-out scenarios (the set of `fairgrasp eval --seed EVAL_SEED`) with its 95 % Wilson interval.

    python python/examples/sb3_ppo.py --preset sector --timesteps 200000
    python python/examples/sb3_ppo.py --preset place --timesteps 200000

Its reporting step, `report`, is tested with a stub model in python/tests/test_examples.py.
"""

import argparse

import fairgrasp
from fairgrasp.compare import describe


def parse_args(argv=None):
    parser = argparse.ArgumentParser()
    parser.add_argument("--preset", default="sector")
    parser.add_argument("--timesteps", type=int, default=200_000)
    parser.add_argument("--envs", type=int, default=8)
    parser.add_argument("--episodes", type=int, default=100)
    parser.add_argument("--eval-seed", type=int, default=7,
                        help="held-out scenarios: the set of fairgrasp eval --seed EVAL_SEED")
    return parser.parse_args(argv)


def report(model, args):
    """The reporting step: ``model`` (anything with SB3's ``predict``) on ``args.episodes``
    held-out scenarios of ``args.preset``; prints and returns the ``fairgrasp.evaluate`` result."""
    result = fairgrasp.evaluate(model, args.preset, args.episodes, args.eval_seed, name="SB3 PPO")
    print(f"SB3 PPO on {args.preset}: {describe(result)}")
    return result


def main(argv=None):
    from stable_baselines3 import PPO

    from fairgrasp.sb3 import FairGraspVecEnv

    args = parse_args(argv)
    env = FairGraspVecEnv(args.envs, preset=args.preset, threads=2, seed=0)
    model = PPO("MlpPolicy", env, n_steps=256, batch_size=256, seed=0, verbose=1)
    model.learn(total_timesteps=args.timesteps)
    model.save(f"ppo_fairgrasp_{args.preset}")
    report(model, args)


if __name__ == "__main__":
    main()
