"""Pure SB3 PPO on the env the `pure_full` recipe trains on, with the recipe's hyperparameters:
`FairGraspVecEnv(8, recipe="pure_full")` (task-space action, binary gripper, staged reward,
100-step episodes, the Rust curriculum shared by the 8 envs), observations normalised as
`norm_obs` does (SB3's VecNormalize, rewards left alone), and every `--eval-every` steps a
deterministic evaluation on held-out scenarios of the `--presets` (default `fixed` and `sector`;
a place preset such as `place` works too: the preset as it is, the env evaluations use, so the
training-only reward does not matter there). Prints one line per evaluation and writes them to
`--log` (JSON lines).

    python/examples/sb3_venv.sh
    nice -n 10 target/sb3-venv/bin/python python/examples/sb3_pure.py --timesteps 4800000 --log runs/sb3_pure.jsonl

Needs torch and SB3 (the venv above); not part of CI (its reporting step, `evaluation_row`, is
tested with a stub model in python/tests/test_examples.py).
"""

import argparse
import json
import os
import time

import fairgrasp
from fairgrasp.compare import describe
from sb3_common import policy_act, recipe_file


def parse_args(argv=None):
    parser = argparse.ArgumentParser()
    parser.add_argument("--recipe", default="pure_full")
    parser.add_argument("--timesteps", type=int, default=4_800_000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--eval-every", type=int, default=100_000)
    parser.add_argument("--eval-episodes", type=int, default=100)
    parser.add_argument("--eval-seed", type=int, default=7,
                        help="held-out scenarios: the set of fairgrasp eval --seed EVAL_SEED")
    parser.add_argument("--presets", nargs="+", default=["fixed", "sector"], help="the presets evaluated on")
    parser.add_argument("--log", default=None)
    parser.add_argument("--save", default=None, help="save the model and VecNormalize statistics here at the end")
    return parser.parse_args(argv)


def evaluation_row(model, normalizer, args, row):
    """The reporting step: ``row`` (the training's figures) with ``model``'s deterministic
    evaluation on ``args.eval_episodes`` held-out scenarios of each of ``args.presets`` (through
    ``normalizer``'s statistics if given), printed as one JSON line and appended to
    ``args.log``; returns the row."""
    act = policy_act(model, normalizer)
    for preset in args.presets:
        r = fairgrasp.evaluate(act, preset, args.eval_episodes, args.eval_seed, recipe=args.recipe)
        row[preset] = {"successes": r["successes"], "episodes": r["episodes"], "outcomes": r["outcomes"]}
        row[preset + "_text"] = describe(r)
    print(json.dumps(row), flush=True)
    if args.log:
        with open(args.log, "a") as f:
            f.write(json.dumps(row) + "\n")
    return row


def train(args):
    """Trains with an evaluation every ``args.eval_every`` steps and one at the end."""
    from stable_baselines3.common.callbacks import BaseCallback
    from stable_baselines3.common.vec_env import VecNormalize

    from fairgrasp.sb3 import FairGraspVecEnv
    from sb3_common import ppo_from_recipe

    recipe = recipe_file(args.recipe)
    # Training scenarios from the upper part of the seed space (held-out sets use seed · 1 000 003 + i).
    venv = FairGraspVecEnv(recipe["n_envs"], recipe=args.recipe, threads=recipe["threads"], seed=(1 << 62) + args.seed)
    env = VecNormalize(venv, norm_obs=recipe["ppo"].get("norm_obs", True), norm_reward=False, clip_obs=10.0)
    model = ppo_from_recipe(env, recipe, args.seed)

    class Progress(BaseCallback):
        def __init__(self):
            super().__init__()
            self.start = time.time()
            self.next_eval = args.eval_every
            self.recent = []

        def _on_step(self):
            for info in self.locals["infos"]:
                if "is_success" in info:
                    self.recent = (self.recent + [info["is_success"]])[-200:]
            if self.num_timesteps >= self.next_eval:
                self.next_eval += args.eval_every
                self.report()
            return True

        def report(self):
            elapsed = time.time() - self.start
            evaluation_row(self.model, env, args, {
                "timesteps": self.num_timesteps,
                "wall_s": round(elapsed, 1),
                "steps_per_s": round(self.num_timesteps / elapsed, 1),
                "stage": venv.curriculum_stage,
                "train_success_last_200": sum(self.recent) / max(1, len(self.recent)),
                "load_avg": os.getloadavg()[0],
            })

    callback = Progress()
    model.learn(total_timesteps=args.timesteps, callback=callback)
    callback.report()
    return model, env


def main(argv=None):
    args = parse_args(argv)
    model, env = train(args)
    if args.save:
        model.save(args.save)
        env.save(args.save + ".vecnormalize.pkl")


if __name__ == "__main__":
    main()
