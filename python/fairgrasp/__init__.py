"""fairgrasp from Python: the Rust grasping env for the FAIRINO FR3 as a gymnasium env.

    import gymnasium as gym
    import fairgrasp  # registers FairGrasp-v0 and one id per preset
    env = gym.make("FairGrasp-v0", preset="full", arm="servo")

Also: ``fairgrasp.VectorEnv`` (N envs on Rust threads), ``fairgrasp.sb3.FairGraspVecEnv``
(Stable-Baselines3's own VecEnv interface), ``fairgrasp.kinematics`` (FK, closed-form and QP IK,
world_to_base), ``fairgrasp.Baseline`` (the scripted grasp as a policy) and
``fairgrasp.ResidualWrapper`` (the baseline's action in the observation, the policy's action
added to it).
"""

from . import _native, kinematics
from ._native import ACT_DIM, OBS_DIM, preset_names
from .baseline import Baseline
from .env import FairGraspEnv
from .registration import register_all
from .residual import ResidualWrapper
from .vector import VectorEnv

__all__ = [
    "ACT_DIM",
    "OBS_DIM",
    "Baseline",
    "FairGraspEnv",
    "ResidualWrapper",
    "VectorEnv",
    "kinematics",
    "preset_names",
    "register_all",
]

register_all()
