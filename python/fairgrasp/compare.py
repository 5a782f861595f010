"""``fairgrasp.compare``: the report of ``fairgrasp compare`` with Python policies in it.

    import fairgrasp
    model = PPO.load("my_residual.zip")                          # trained on fairgrasp.make("residual_miscalibrated", preset="nudged")
    fairgrasp.compare(
        policies={"my SB3 residual": {"policy": model, "recipe": "residual_miscalibrated"},
                  "mine, from Rust": fairgrasp.load_policy("runs/res/checkpoints/best")},
        presets=["nudged", "full"], episodes=300, seed=7, out="my_report")

The scripts and (unless ``shipped=False``) the shipped policies run in Rust on each preset's
seeded scenarios; each Python policy plays the very same scenarios through
``fairgrasp.evaluate``; the folder ``out`` then holds what ``fairgrasp compare`` writes (tables,
``compare.json``/``.csv``, paired tests of every learned method against each script, charts,
the notebook, replays of the Rust methods), written whole or not at all.
"""

import json
import os

from . import _native
from .presets import current_preset
from .policy import evaluate


def _method(value):
    """``(policy, keyword arguments of evaluate)`` of a method given as a policy or a dict."""
    if isinstance(value, dict):
        unknown = set(value) - {"policy", "recipe", "agent", "vec_normalize"}
        if unknown or "policy" not in value:
            raise ValueError(
                f"a method given as a dict has the keys policy, recipe, agent, vec_normalize; got {sorted(value)}"
            )
        extra = {k: value[k] for k in ("recipe", "agent", "vec_normalize") if k in value}
        return value["policy"], extra
    return value, {}


def compare(policies=None, presets=None, episodes=100, seed=0, out="report", *, force=False,
            arm="servo", threads=None, shipped=True):
    """Writes the comparison report folder ``out`` with ``policies`` (``{"name": policy}``, a
    policy being anything ``fairgrasp.evaluate`` takes, or ``{"policy": p, "recipe": r,
    "agent": a, "vec_normalize": v}`` for a model trained on a recipe's env, ``v`` the
    ``VecNormalize`` it was trained behind when the model does not carry it) beside the scripts and the shipped
    policies. ``presets``: default ``fairgrasp compare``'s. ``out`` must be new, empty, or (with
    ``force=True``) a report fairgrasp wrote. Returns the files written (relative to ``out``).

    A policy that raises or returns a bad action raises ``fairgrasp.PolicyError`` naming it, the
    preset and the step, and nothing is written to ``out``."""
    presets = [current_preset(p) for p in presets] if presets is not None else _native.default_compare_presets()
    policies = dict(policies or {})
    out = str(out)
    parsed = {name: _method(value) for name, value in policies.items()}  # before any file is touched
    _native.check_compare(presets, int(episodes), int(seed), out, bool(force), arm, threads)
    methods = []
    for name, (policy, extra) in parsed.items():
        results = []
        for preset in presets:
            r = evaluate(policy, preset, episodes, seed, arm=arm, name=name, **extra)
            results.append([preset, r["records"]])
        origin = getattr(policy, "name", None) or type(policy).__name__
        methods.append({"name": str(name), "policy": f"python: {origin}", "results": results})
    command = f"fairgrasp.compare(policies={list(policies)}, presets={presets}, episodes={episodes}, seed={seed})"
    return list(_native.compare(presets, int(episodes), int(seed), out, json.dumps(methods),
                                bool(force), arm, threads, bool(shipped), command))


def read_comparison(out):
    """The ``compare.json`` of the report folder ``out``, as a dict."""
    with open(os.path.join(os.fspath(out), "compare.json")) as f:
        return json.load(f)


def scripts_of(comparison, preset):
    """The results of the task's scripts on ``preset`` in ``comparison`` (``compare.json`` as a
    dict), in the comparison's run order: the methods without a policy folder, which Rust's
    table of controls runs first, the task's open-loop script first (``scripted baseline`` on a
    lift preset, ``place script`` on a place preset). Nothing here knows their names."""
    order = {name: i for i, name in enumerate(comparison["methods"])}
    found = [r for r in comparison["results"] if r["preset"] == preset and r.get("policy") is None]
    return sorted(found, key=lambda r: order[r["method"]])


def versus_script(comparison, method, preset):
    """``method``'s result on ``preset`` beside the task's open-loop script's (the first of
    ``scripts_of``): a dict with ``method`` and ``script`` (their ``compare.json`` results) and
    ``difference_points``, the method's success rate minus the script's in percentage points
    (of success within the takt on a task with a takt, which is what its paired tests count).
    A method or preset the comparison does not have is a ValueError naming what it has."""
    found = [r for r in comparison["results"] if r["method"] == method and r["preset"] == preset]
    scripts = scripts_of(comparison, preset)
    if not found or not scripts:
        raise ValueError(
            f"the comparison has no {'script' if found else repr(method)} on preset {preset!r}: its "
            f"methods are {comparison['methods']}, its presets {comparison['presets']}"
        )
    trained, script = found[0], scripts[0]
    key = "within_takt_rate" if trained.get("takt_s") is not None else "success_rate"
    return {
        "method": trained,
        "script": script,
        "difference_points": round(100 * (trained[key] - script[key]), 1),
    }


def describe(result):
    """``k/n = x % (95 % CI lo–hi %)`` of a ``compare.json`` or ``evaluate`` result, and on a
    task with a takt also its success within the takt and its mean cycle time."""
    k, n = result["successes"], result["episodes"]
    text = (f"{k}/{n} = {100 * k / n:.1f} % "
            f"(95 % CI {100 * result['ci_low']:.1f}–{100 * result['ci_high']:.1f} %)")
    if result.get("takt_s") is not None:
        cycle = result.get("mean_cycle_time_s")
        text += (f"; within the {result['takt_s']:g} s takt {result['successes_within_takt']}/{n} = "
                 f"{100 * result['within_takt_rate']:.1f} % (95 % CI {100 * result['within_takt_ci_low']:.1f}–"
                 f"{100 * result['within_takt_ci_high']:.1f} %), mean cycle "
                 + ("–" if cycle is None else f"{cycle:.1f} s"))
    return text
