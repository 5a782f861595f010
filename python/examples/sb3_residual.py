"""SB3 PPO on the task-space residual env (the env `fairgrasp train` steps for the preset's
residual recipe: `residual_miscalibrated` on a lift preset such as `nudged`, the place task's on a
place preset; `--recipe` picks another): the observation is the residual policy's input
(observation and the script's features), the action the correction, both computed by the Rust
agent code. The recipe's hyperparameters, the actor's output layer zeroed (the untrained policy
is the open-loop script; SB3 has no critic warm-up, so the recipe's critic-only updates are left
out). At the end, `fairgrasp.compare` writes the report folder `--out`: the trained SB3 policy
beside the task's scripts (and the shipped policies with `--shipped`) on the same `--episodes`
held-out scenarios, with 95 % Wilson intervals and McNemar's paired test against each script.

    python/examples/sb3_venv.sh
    nice -n 10 target/sb3-venv/bin/python python/examples/sb3_residual.py --preset nudged --timesteps 300000 --out runs/sb3_residual_report
    nice -n 10 target/sb3-venv/bin/python python/examples/sb3_residual.py --preset place_tilted --out runs/sb3_residual_place

Needs torch and SB3 (the venv above); not part of CI (its reporting step, `report`, is tested
with a stub model in python/tests/test_examples.py).
"""

import json
import time

from report_step import compare_with_scripts, residual_parser, with_recipe
from sb3_common import policy_act, recipe_file

NAME = "SB3 PPO residual"


def parse_args(argv=None):
    parser = residual_parser("runs/sb3_residual_report")
    parser.add_argument("--log", default=None)
    parser.add_argument("--shipped", action="store_true", help="put the shipped policies in the report too")
    return with_recipe(parser.parse_args(argv))


def train(args):
    """SB3 PPO trained on the recipe's env: ``(model, VecNormalize env, wall seconds)``."""
    from stable_baselines3.common.callbacks import BaseCallback
    from stable_baselines3.common.vec_env import VecNormalize

    from fairgrasp.sb3 import FairGraspVecEnv
    from sb3_common import ppo_from_recipe

    class Progress(BaseCallback):
        def __init__(self):
            super().__init__()
            self.start, self.recent, self.next = time.time(), [], 20_000

        def _on_step(self):
            for info in self.locals["infos"]:
                if "is_success" in info:
                    self.recent = (self.recent + [info["is_success"]])[-200:]
            if self.num_timesteps >= self.next:
                self.next += 20_000
                rate = self.num_timesteps / (time.time() - self.start)
                print(f"{self.num_timesteps} steps, {rate:.0f} steps/s, training success (last 200 episodes) "
                      f"{100 * sum(self.recent) / max(1, len(self.recent)):.0f} %", flush=True)
            return True

    recipe = recipe_file(args.recipe)
    venv = FairGraspVecEnv(recipe["n_envs"], recipe=args.recipe, preset=args.preset, threads=recipe["threads"],
                           seed=(1 << 62) + args.seed)
    env = VecNormalize(venv, norm_obs=recipe["ppo"].get("norm_obs", True), norm_reward=False, clip_obs=10.0)
    model = ppo_from_recipe(env, recipe, args.seed)
    start = time.time()
    model.learn(total_timesteps=args.timesteps, callback=Progress())
    return model, env, time.time() - start


def report(model, normalizer, args, train_s):
    """The reporting step: ``model`` (anything with SB3's ``predict``, seen through
    ``normalizer``'s ``normalize_obs`` if given) in the report folder ``args.out`` beside the
    task's scripts; prints the result against the open-loop script and returns it as one JSON
    row (also appended to ``args.log``)."""
    pair = compare_with_scripts(NAME, policy_act(model, normalizer), recipe=args.recipe, preset=args.preset,
                                episodes=args.episodes, eval_seed=args.eval_seed, out=args.out,
                                force=args.force, shipped=args.shipped)
    trained, script = pair["method"], pair["script"]
    row = {
        "recipe": args.recipe, "preset": args.preset, "timesteps": args.timesteps, "train_wall_s": round(train_s, 1),
        "steps_per_s": round(args.timesteps / train_s, 1) if train_s > 0 else None,
        "episodes": args.episodes, "eval_seed": args.eval_seed,
        "trained": trained["successes"], "trained_outcomes": trained["outcomes"],
        "script_name": script["method"], "script": script["successes"], "script_outcomes": script["outcomes"],
        "difference_points": pair["difference_points"],
        "report": args.out,
    }
    print(json.dumps(row))
    if args.log:
        with open(args.log, "a") as f:
            f.write(json.dumps(row) + "\n")
    return row


def main(argv=None):
    args = parse_args(argv)
    model, env, train_s = train(args)
    report(model, env, args, train_s)


if __name__ == "__main__":
    main()
