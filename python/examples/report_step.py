"""The reporting step the residual training examples share (sb3_residual.py, rllib_ppo.py): the
trained policy in ``fairgrasp.compare``'s report folder beside the task's scripts on held-out
scenarios, then its result against the task's open-loop script. The scripts are found in the
report's ``compare.json`` (``fairgrasp.compare.versus_script``), so the step runs on a lift and on
a place preset alike. No SB3, torch or Ray here: python/tests/test_examples.py runs it with a
stub policy."""

import argparse

import fairgrasp
from fairgrasp.compare import describe, read_comparison, versus_script
from fairgrasp.recipes import task_residual_recipe


def residual_parser(out):
    """The arguments every residual training example takes (the report folder ``out`` by
    default); an example adds its own."""
    parser = argparse.ArgumentParser()
    parser.add_argument("--recipe", default=None,
                        help="the recipe whose env and hyperparameters to use (default: the preset's residual recipe)")
    parser.add_argument("--preset", default="nudged")
    parser.add_argument("--timesteps", type=int, default=300_000)
    parser.add_argument("--seed", type=int, default=0, help="training seed, 0–999 999")
    parser.add_argument("--episodes", type=int, default=300)
    parser.add_argument("--eval-seed", type=int, default=7,
                        help="held-out scenarios: the set of fairgrasp eval --seed EVAL_SEED")
    parser.add_argument("--out", default=out, help="the report folder fairgrasp.compare writes")
    parser.add_argument("--force", action="store_true", help="replace an earlier report in --out")
    return parser


def with_recipe(args):
    """``args`` with ``--recipe`` left out set to the preset's residual recipe."""
    if args.recipe is None:
        args.recipe = task_residual_recipe(args.preset)
    return args


def compare_with_scripts(name, act, *, recipe, preset, episodes, eval_seed, out, force=False,
                         shipped=False):
    """Writes the report folder ``out`` with the policy ``act`` (a callable ``obs -> action`` on
    ``recipe``'s env) called ``name`` beside the scripts of ``preset``'s task (and the shipped
    policies with ``shipped``) on ``episodes`` scenarios of the held-out set ``eval_seed``;
    prints and returns ``fairgrasp.compare.versus_script`` of it."""
    fairgrasp.compare(policies={name: {"policy": act, "recipe": recipe}}, presets=[preset],
                      episodes=episodes, seed=eval_seed, out=out, force=force, shipped=shipped)
    pair = versus_script(read_comparison(out), name, preset)
    print(f"{name}: {describe(pair['method'])}")
    print(f"{pair['script']['method']} (the task's open-loop script): {describe(pair['script'])}")
    print(f"difference: {pair['difference_points']:+.1f} points; report with the paired tests: {out}/report.md")
    return pair
