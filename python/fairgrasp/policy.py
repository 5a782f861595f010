"""Trained policies and their evaluation from Python.

    import fairgrasp
    policy = fairgrasp.load_policy("residual_nudged")        # a shipped name, a checkpoint or run folder
    env = policy.make_env("nudged")                           # the env whose observation it takes
    obs, info = env.reset(seed=7)
    action, _ = policy.predict(obs, deterministic=True)       # Stable-Baselines3's signature
    result = fairgrasp.evaluate(policy, "nudged", episodes=300, seed=7)   # = fairgrasp eval

``evaluate`` plays the scenarios ``fairgrasp eval --preset P --episodes N --seed S`` plays, in the
same order, with any policy: a ``load_policy`` policy, anything with SB3's ``predict`` (an SB3
model trained on ``fairgrasp.make(recipe)``: pass that ``recipe``), or a callable ``obs ->
action``. Outcomes are Rust's episode records, never re-derived here.
"""

import json
import math
from collections import Counter

import numpy as np

from . import _native
from .env import FairGraspEnv
from .presets import current_preset
from .recipes import make


class PolicyError(ValueError):
    """A policy that raised, or returned an action of the wrong shape or a non-finite one: the
    message names the policy, the preset, the scenario and the step."""


class RustPolicy:
    """A trained fairgrasp policy (``fairgrasp.load_policy``): the network of ``fairgrasp eval``
    (the same burn-free actor, the observation normalised with the checkpoint's statistics, the
    mean action). Its observation and action are those of the env ``make_env`` gives: for a
    residual, the residual policy's input and the correction of the script."""

    def __init__(self, name_or_folder):
        self._native = _native.NativePolicy(str(name_or_folder))
        self.agent = json.loads(self._native.agent_json())
        self.name = str(name_or_folder)

    def __repr__(self):
        return f"RustPolicy({self.name!r}, agent={self.agent})"

    @property
    def trained_timesteps(self):
        return self._native.trained_timesteps

    def predict(self, observation, state=None, episode_start=None, deterministic=True):
        """Stable-Baselines3's ``predict``: ``(action, state)`` for one observation or a batch.
        The policy is deterministic (its mean action) and keeps no state."""
        obs = np.asarray(observation, dtype=np.float32)
        single = obs.ndim == 1
        actions = self._native.predict_batch(np.ascontiguousarray(obs.reshape(1, -1) if single else obs))
        return (actions[0] if single else actions), state

    def make_env(self, preset="sector", arm="servo", render_mode=None):
        """The env this policy acts in, as ``fairgrasp eval`` evaluates it: the preset as it is
        (no curriculum, no training overrides), seen through the policy's agent."""
        recipe = "pure_full" if self.agent.get("mode") == "pure" else "residual_miscalibrated"
        return make(recipe, preset=preset, arm=arm, agent=self.agent, evaluation=True,
                    render_mode=render_mode)


def load_policy(name_or_folder):
    """A shipped policy by name (``residual_nudged``, ``pure_full``, …), a checkpoint folder
    (``meta.json`` inside) or a run folder (its ``checkpoints/best``), checked as ``fairgrasp
    eval`` checks it (checksums, ranges)."""
    return RustPolicy(name_or_folder)


#: ``vec_normalize`` not given: take an SB3 model's own (``model.get_vec_normalize_env()``).
FROM_MODEL = "from the model"


def _normalizer(policy, vec_normalize):
    """The observation normaliser an SB3 model was trained behind, or None: ``vec_normalize`` if
    given (None: none), else the model's own. A model without its env (``PPO.load`` without
    ``env=``) is refused: whether it was trained behind ``VecNormalize`` cannot be known, and
    unnormalised inputs would evaluate it wrongly without a word."""
    if vec_normalize is not FROM_MODEL:
        return vec_normalize
    if not hasattr(policy, "get_vec_normalize_env"):
        return None
    found = policy.get_vec_normalize_env()
    if found is None and getattr(policy, "env", None) is None:
        raise ValueError(
            f"policy {type(policy).__name__}: an SB3 model without its env, so its VecNormalize "
            "statistics (if it was trained behind VecNormalize) are unknown; pass "
            "vec_normalize=VecNormalize.load(path, venv) (in compare: {'policy': model, "
            "'vec_normalize': ...}), or vec_normalize=None if it was trained without one"
        )
    return found


def _actor(policy, vec_normalize=FROM_MODEL):
    if hasattr(policy, "predict"):
        normalizer = _normalizer(policy, vec_normalize)
        if normalizer is None:
            return lambda obs: policy.predict(obs, deterministic=True)[0]
        return lambda obs: policy.predict(normalizer.normalize_obs(obs[None, :])[0], deterministic=True)[0]
    if vec_normalize is not FROM_MODEL and vec_normalize is not None:
        raise ValueError("vec_normalize= is for an SB3 model (an object with predict)")
    if callable(policy):
        return policy
    raise TypeError(f"policy {policy!r}: expected an object with predict(obs) or a callable obs -> action")


def _env_for(policy, preset, arm, recipe, agent):
    if isinstance(policy, RustPolicy):
        if recipe is not None or agent is not None:
            raise ValueError("a load_policy policy brings its own env: leave out recipe and agent")
        return policy.make_env(preset, arm)
    if recipe is not None:
        overrides = {"agent": agent} if agent is not None else {}
        return make(recipe, preset=preset, arm=arm, evaluation=True, **overrides)
    if agent is not None:
        raise ValueError("agent= needs recipe=")
    return FairGraspEnv(preset=preset, arm=arm)


def evaluate(policy, preset="sector", episodes=100, seed=0, *, arm="servo", recipe=None, agent=None,
             name=None, vec_normalize=FROM_MODEL):
    """Plays ``episodes`` scenarios of ``preset`` (the list ``fairgrasp eval --seed seed`` plays)
    with ``policy`` and returns a dict: ``success_rate``, ``successes``, ``episodes``, the 95 %
    Wilson interval ``ci_low`` / ``ci_high``, ``outcomes`` (counts by Rust's outcome names) and
    ``records`` (one Rust episode record per episode; its ``seed`` is the scenario's).

    The env: a ``load_policy`` policy's own; else the env of ``recipe`` (the one an SB3 model was
    trained on, ``agent`` laid over it) as evaluations use it; else the preset's plain env.
    An SB3 model sees the observations through the ``VecNormalize`` it was trained behind: its own
    (``model.get_vec_normalize_env()``), or ``vec_normalize`` (None: none); a model loaded
    without its env and without ``vec_normalize`` is refused (ValueError).
    A policy that raises, or returns a wrong shape or a non-finite action, raises
    ``PolicyError`` naming the policy, the preset, the scenario and the step."""
    label = name or getattr(policy, "name", None) or type(policy).__name__
    preset = current_preset(preset)
    act = _actor(policy, vec_normalize)
    env = _env_for(policy, preset, arm, recipe, agent)
    shape = env.action_space.shape
    seeds = _native.scenario_seeds(preset, int(seed), int(episodes), arm)
    records = []
    for k, scenario_seed in enumerate(seeds):
        obs, info = env.reset(seed=scenario_seed)
        step = 0
        while True:
            where = f"policy {label!r} on preset {preset!r}, episode {k} (scenario seed {scenario_seed}), step {step}"
            try:
                action = np.asarray(act(obs), dtype=np.float64)
            except Exception as e:  # the policy's own failure, reported with where it happened
                raise PolicyError(f"{where}: the policy raised {type(e).__name__}: {e}") from e
            if action.shape != shape:
                raise PolicyError(f"{where}: the action has shape {action.shape}, expected {shape}")
            bad = np.flatnonzero(~np.isfinite(action))
            if bad.size:
                raise PolicyError(f"{where}: action[{bad[0]}] = {action[bad[0]]} is not finite")
            obs, _, terminated, truncated, info = env.step(action)
            step += 1
            if terminated or truncated:
                records.append(dict(info["episode_record"]))
                break
    outcomes = Counter(r["outcome"] for r in records)
    successes = outcomes.get("success", 0)
    low, high = _native.wilson_interval(successes, len(records))
    return {
        "policy": label,
        "preset": preset,
        "seed": int(seed),
        "episodes": len(records),
        "successes": successes,
        "success_rate": successes / len(records) if records else math.nan,
        "ci_low": low,
        "ci_high": high,
        "outcomes": dict(outcomes),
        "records": records,
    }
