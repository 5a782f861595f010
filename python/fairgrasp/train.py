"""The Rust PPO trainer from Python: ``fairgrasp.train(config, run_dir, **overrides)`` runs
``fairgrasp train`` in this process (the GIL released while it trains), writing the same run
folder (``config.toml``, ``metrics.csv``, ``checkpoints/``, ``eval.json``).

    import fairgrasp
    report = fairgrasp.train("residual_miscalibrated", "runs/nudged_s1", preset="nudged", seed=1,
                             progress=lambda p: print(p["timesteps"], p["success"]))
    report["success_rate"], report["ci_low"], report["ci_high"], report["outcomes"]

``config``: a shipped recipe's name (``fairgrasp.recipe_names()``) or a training config's path;
``overrides``: any of the config's keys (``seed``, ``total_timesteps``, ``preset``,
``ppo={"learning_rate": 1e-4}``, ...; tables merge key by key; a misspelt key is refused with the
valid ones). Needs the extension built with the trainer, which links burn (minutes of compiling)
and which ``pip install ./python`` and the wheel of ``scripts/build-wheel.sh`` leave out unless
asked for (``HOW_TO_GET_THE_TRAINER`` says how); the test build (``cargo test --workspace``) has it.
"""

import json
import os
import sys

from . import _native
from .presets import current_preset


#: How to get an extension with the trainer, in the error ``train`` raises without one.
HOW_TO_GET_THE_TRAINER = (
    'pip install ./python --config-settings=build-args="--features train" '
    "(from a clone of the repository; or scripts/build-wheel.sh --features train, then pip install "
    "the wheel it prints)"
)


def require_trainer(native=None):
    """Raises RuntimeError saying how to get the trainer when the extension ``native`` (default:
    this package's) was built without it (``HAS_TRAIN`` false)."""
    if not getattr(_native if native is None else native, "HAS_TRAIN", False):
        raise RuntimeError(
            "fairgrasp.train: this build of fairgrasp has no Rust trainer (it was built without the "
            "cargo feature `train`, which compiles burn; the envs, evaluate, compare and load_policy "
            f"work without it). To train from Python, reinstall with it: {HOW_TO_GET_THE_TRAINER}"
        )


def _bar(p):
    eval_part = "" if p["eval"] is None else f" eval {100 * p['eval']:.0f}%"
    print(
        f"\r{p['timesteps']}/{p['total']} steps  success {100 * p['success']:.0f}%  "
        f"return {p['mean_return']:.2f}  stage {p['stage']}{eval_part}   ",
        end="", file=sys.stderr, flush=True,
    )


def train(config, run_dir, *, resume=False, force=False, progress=None, **overrides):
    """Trains ``config`` with ``overrides`` in ``run_dir`` (``resume=True`` continues it;
    ``force=True`` moves a run the folder holds aside to ``run_dir.replaced-N`` and starts over);
    ``progress``: a callable given a dict after every update (``timesteps``, ``total``,
    ``stage``, ``eval``, ``episodes``, ``success``, ``mean_return``), or ``True`` for a one-line
    bar on stderr. Returns the final evaluation as a dict (``eval.json``'s report)."""
    require_trainer()
    callback = _bar if progress is True else progress
    if "preset" in overrides:
        overrides["preset"] = current_preset(overrides["preset"])
    if "mix" in overrides and overrides["mix"] is not None:
        overrides["mix"] = [current_preset(p) for p in overrides["mix"]]
    overrides_json = json.dumps(overrides) if overrides else None
    report = _native.train(str(config), os.fspath(run_dir), overrides_json, bool(resume), callback,
                            bool(force))
    if progress is True:
        print(file=sys.stderr)
    return report
