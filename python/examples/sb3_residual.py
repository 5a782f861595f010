"""SB3 PPO on the task-space residual env (the env `fairgrasp train` steps for the
`residual_miscalibrated` recipe, here on `--preset nudged`): the observation is the residual
policy's input (observation and the script's 19 features), the action the correction, both
computed by the Rust agent code. The recipe's hyperparameters, the actor's output layer zeroed
(the untrained policy is the open-loop script; SB3 has no critic warm-up, so the recipe's 5
critic-only updates are left out). At the end, `fairgrasp.compare` writes the report folder
`--out`: the trained SB3 policy beside the scripts (and the shipped policies with `--shipped`)
on the same `--episodes` held-out scenarios, with 95 % Wilson intervals and McNemar's paired
test against each script.

    python/examples/sb3_venv.sh
    nice -n 10 target/sb3-venv/bin/python python/examples/sb3_residual.py --preset nudged --timesteps 300000 --out runs/sb3_residual_report

Needs torch and SB3 (the venv above); not part of CI.
"""

import argparse
import json
import time

from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.vec_env import VecNormalize

import fairgrasp
from fairgrasp.sb3 import FairGraspVecEnv
from sb3_common import policy_act, ppo_from_recipe, recipe_file

parser = argparse.ArgumentParser()
parser.add_argument("--recipe", default="residual_miscalibrated")
parser.add_argument("--preset", default="nudged")
parser.add_argument("--timesteps", type=int, default=300_000)
parser.add_argument("--seed", type=int, default=0)
parser.add_argument("--episodes", type=int, default=300)
parser.add_argument("--eval-seed", type=int, default=7, help="held-out scenarios: the set of fairgrasp eval --seed EVAL_SEED")
parser.add_argument("--log", default=None)
parser.add_argument("--out", default="runs/sb3_residual_report", help="the report folder fairgrasp.compare writes")
parser.add_argument("--shipped", action="store_true", help="put the shipped policies in the report too")
parser.add_argument("--force", action="store_true", help="replace an earlier report in --out")
args = parser.parse_args()

recipe = recipe_file(args.recipe)
venv = FairGraspVecEnv(recipe["n_envs"], recipe=args.recipe, preset=args.preset, threads=recipe["threads"],
                       seed=(1 << 62) + args.seed)
env = VecNormalize(venv, norm_obs=recipe["ppo"].get("norm_obs", True), norm_reward=False, clip_obs=10.0)
model = ppo_from_recipe(env, recipe, args.seed)


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


start = time.time()
model.learn(total_timesteps=args.timesteps, callback=Progress())
train_s = time.time() - start
name = "SB3 PPO residual"
fairgrasp.compare(policies={name: {"policy": policy_act(model, env), "recipe": args.recipe}},
                  presets=[args.preset], episodes=args.episodes, seed=args.eval_seed, out=args.out,
                  force=args.force, shipped=args.shipped)
with open(f"{args.out}/compare.json") as f:
    comparison = json.load(f)
results = {r["method"]: r for r in comparison["results"]}
trained, script = results[name], results["scripted baseline"]
row = {
    "preset": args.preset, "timesteps": args.timesteps, "train_wall_s": round(train_s, 1),
    "steps_per_s": round(args.timesteps / train_s, 1), "episodes": args.episodes, "eval_seed": args.eval_seed,
    "trained": trained["successes"], "trained_outcomes": trained["outcomes"],
    "script": script["successes"], "script_outcomes": script["outcomes"],
    "difference_points": round(100 * (trained["success_rate"] - script["success_rate"]), 1),
    "report": args.out,
}
print(f"{name}: {trained['successes']}/{args.episodes} = {100 * trained['success_rate']:.1f} % "
      f"(95 % CI {100 * trained['ci_low']:.1f}–{100 * trained['ci_high']:.1f} %)")
print(f"open-loop script: {script['successes']}/{args.episodes} = {100 * script['success_rate']:.1f} % "
      f"(95 % CI {100 * script['ci_low']:.1f}–{100 * script['ci_high']:.1f} %)")
print(f"report with the paired tests: {args.out}/report.md")
print(json.dumps(row))
if args.log:
    with open(args.log, "a") as f:
        f.write(json.dumps(row) + "\n")
