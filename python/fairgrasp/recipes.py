"""The training recipes of ``assets/experiments/`` from Python: ``make`` gives the env a recipe
trains on (one env), ``make_vec`` the native vector env of it (one curriculum shared by all
envs, as ``fairgrasp train`` shares it).

    import fairgrasp
    env = fairgrasp.make("pure_full")                      # = gym.make("FairGrasp-Recipe-PureFull-v0")
    env = fairgrasp.make("residual_miscalibrated", preset="nudged")
    env = fairgrasp.make("pure_full", env={"task": {"max_steps": 50}}, curriculum=None)
    env = fairgrasp.make("pure_full", preset="sector", evaluation=True)   # the env evaluations use

Overrides: ``preset``, ``arm``, ``agent``, ``curriculum``, ``env`` (``recipe_keys()``), laid over
the recipe as tables (nested dicts merge key by key), ``None`` drops a key; a misspelt key is
refused with the list of valid ones.
"""

from . import _native
from .env import FairGraspEnv
from .presets import current_preset
from .vector import VectorEnv


def recipe_names():
    """The shipped recipes (``assets/experiments/<name>.toml``)."""
    return list(_native.recipe_names())


def recipe_keys():
    """The keys an override may have."""
    return list(_native.recipe_keys())


def task_residual_recipe(preset):
    """The shipped recipe of the task-space residual for the shipped preset ``preset``: the
    lift task's (``residual_miscalibrated``) on a lift preset, the place task's on a place
    preset; an unknown preset is a ValueError."""
    return _native.task_residual_recipe(current_preset(preset))


def make(recipe, *, render_mode=None, evaluation=False, **overrides):
    """The env ``recipe`` (a shipped name or a training config's path) trains on, with
    ``overrides`` laid over it (see the module doc)."""
    return FairGraspEnv(recipe=recipe, render_mode=render_mode, evaluation=evaluation, **overrides)


def make_vec(recipe, num_envs=8, *, threads=2, seed=0, evaluation=False, **overrides):
    """``num_envs`` envs of ``recipe`` on ``threads`` Rust threads (``fairgrasp.VectorEnv``)."""
    return VectorEnv(num_envs=num_envs, threads=threads, seed=seed, recipe=recipe, evaluation=evaluation, **overrides)
