"""The reporting step the residual training examples share (sb3_residual.py, rllib_ppo.py): the
trained policy in ``fairgrasp.compare``'s report folder beside the task's scripts on held-out
scenarios, then its result against the task's open-loop script. The scripts are found in the
report's ``compare.json`` (``fairgrasp.compare.versus_script``), so the step runs on a lift and on
a place preset alike. No SB3, torch or Ray here: python/tests/test_examples.py runs it with a
stub policy."""

import fairgrasp
from fairgrasp.compare import describe, read_comparison, versus_script


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
