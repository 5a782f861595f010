"""fairgrasp from Python: the Rust grasping env for the FAIRINO FR3 as a gymnasium env.

    import gymnasium as gym
    import fairgrasp  # registers FairGrasp-v0, one id per preset and one per training recipe
    env = gym.make("FairGrasp-v0", preset="full", arm="servo")
    env = fairgrasp.make("pure_full")  # the env a recipe trains on = gym.make("FairGrasp-Recipe-PureFull-v0")

Also: ``fairgrasp.VectorEnv`` (N envs on Rust threads), ``fairgrasp.sb3.FairGraspVecEnv``
(Stable-Baselines3's own VecEnv interface), ``fairgrasp.kinematics`` (FK, closed-form and QP IK,
world_to_base), ``fairgrasp.Baseline`` (the scripted grasp as a policy), and
``fairgrasp.make`` / ``make_vec`` / ``recipe_names`` (the envs of ``assets/experiments/``: for
``residual_*`` recipes the task-space residual env, whose observation is the residual policy's
input and whose action is the correction, computed by the Rust agent code). The first,
joint-space residual (the documented negative result) is
``fairgrasp.make("residual_miscalibrated", agent={"action_space": "joint"})``.
``fairgrasp.train`` runs the Rust PPO trainer (``fairgrasp train``) in this process;
``fairgrasp.load_policy`` loads a trained policy (shipped or a run's) with SB3's ``predict``, and
``fairgrasp.evaluate`` plays ``fairgrasp eval``'s scenarios with any policy, and
``fairgrasp.compare`` writes ``fairgrasp compare``'s report with Python policies in it.
"""

from . import _native, kinematics
from ._native import ACT_DIM, OBS_DIM, preset_names
from .baseline import Baseline
from .compare import compare
from .env import FairGraspEnv
from .policy import PolicyError, RustPolicy, evaluate, load_policy
from .recipes import make, make_vec, recipe_keys, recipe_names
from .registration import register_all
from .train import train
from .vector import VectorEnv

__all__ = [
    "ACT_DIM",
    "OBS_DIM",
    "Baseline",
    "FairGraspEnv",
    "PolicyError",
    "RustPolicy",
    "VectorEnv",
    "compare",
    "evaluate",
    "kinematics",
    "load_policy",
    "make",
    "make_vec",
    "preset_names",
    "recipe_keys",
    "recipe_names",
    "register_all",
    "train",
]

register_all()
