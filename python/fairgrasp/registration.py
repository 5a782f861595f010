"""Registers, each with a native vector entry point:

- ``FairGrasp-v0`` (any preset through ``preset=``) and one id per shipped preset,
  ``FairGrasp-<Preset>-v0`` (e.g. ``FairGrasp-Full-v0``): the bare env, for pure RL;
- one task-space residual per preset, ``FairGrasp-Residual-<Preset>-v0`` (e.g.
  ``FairGrasp-Residual-Nudged-v0``): the env with the script inside, the policy's output a
  correction of it (the id that learns: SB3's PPO takes ``nudged`` from the script's 55 % to
  100 %, docs/python.md); the place presets' correct the force-guided search;
- one id per shipped training recipe, ``FairGrasp-Recipe-<Recipe>-v0`` (e.g.
  ``FairGrasp-Recipe-PureFull-v0``: the env ``assets/experiments/pure_full.toml`` trains on;
  the joint-space residuals' recipes say so: ``FairGrasp-Recipe-JointResidualNudged-v0``).

A renamed preset's old ids (``FairGrasp-Seed-v0``, ``FairGrasp-Residual-Seed-v0``) stay
registered for now: they make the current preset's env, with a ``DeprecationWarning``."""

import gymnasium as gym

from ._native import preset_names, recipe_names, renamed_presets, task_residual_recipe


def _camel(name):
    return "".join(p.capitalize() for p in name.split("_"))


def env_id(preset):
    """The registered id of a preset: ``miscalibrated_b`` → ``FairGrasp-MiscalibratedB-v0``."""
    return "FairGrasp-" + _camel(preset) + "-v0"


def residual_id(preset):
    """The registered id of a preset's task-space residual: ``nudged`` →
    ``FairGrasp-Residual-Nudged-v0``."""
    return "FairGrasp-Residual-" + _camel(preset) + "-v0"


def recipe_id(recipe):
    """The registered id of a recipe: ``pure_full`` → ``FairGrasp-Recipe-PureFull-v0``."""
    return "FairGrasp-Recipe-" + _camel(recipe) + "-v0"


def register_all():
    """Registers every id once (importing fairgrasp twice is harmless)."""
    registered = gym.envs.registry
    ids = [("FairGrasp-v0", {})] + [(env_id(p), {"preset": p}) for p in preset_names()]
    ids += [
        (residual_id(p), {"recipe": task_residual_recipe(p), "preset": p}) for p in preset_names()
    ]
    ids += [(recipe_id(r), {"recipe": r}) for r in recipe_names()]
    for old, new in renamed_presets():
        ids += [
            (env_id(old), {"preset": old}),
            (residual_id(old), {"recipe": task_residual_recipe(new), "preset": old}),
        ]
    for name, kwargs in ids:
        if name in registered:
            continue
        extra = {}
        if _has_vector_entry_point():
            extra["vector_entry_point"] = "fairgrasp.vector:VectorEnv"
        gym.register(
            id=name,
            entry_point="fairgrasp.env:FairGraspEnv",
            kwargs=kwargs,
            **extra,
        )


def _has_vector_entry_point():
    import inspect

    return "vector_entry_point" in inspect.signature(gym.register).parameters
