"""Registers ``FairGrasp-v0`` (any preset through ``preset=``) and one id per shipped preset,
``FairGrasp-<Preset>-v0`` (e.g. ``FairGrasp-Full-v0``), each with a native vector entry point."""

import gymnasium as gym

from ._native import preset_names


def env_id(preset):
    """The registered id of a preset: ``miscalibrated_b`` → ``FairGrasp-MiscalibratedB-v0``."""
    return "FairGrasp-" + "".join(p.capitalize() for p in preset.split("_")) + "-v0"


def register_all():
    """Registers every id once (importing fairgrasp twice is harmless)."""
    registered = gym.envs.registry
    ids = [("FairGrasp-v0", {})] + [(env_id(p), {"preset": p}) for p in preset_names()]
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
