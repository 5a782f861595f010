"""FK/IK from Python equal the CLI's --json; the baseline as a policy object; the residual
wrapper with a zero policy is the baseline."""

import numpy as np
import pytest

import fairgrasp
from fairgrasp import kinematics


@pytest.mark.parametrize("q", [[0.3, -1.2, 1.1, -0.4, 0.9, 0.2], [1, -1, 0.3, -1, 0, 1]])
def test_fk_equals_the_cli(cli, q):
    ours = kinematics.fk(q)
    theirs = cli("fk", "--joints", *map(str, q), "--json")
    for frame in ("flange", "tcp"):
        assert np.allclose(ours[frame]["xyz"], theirs[frame]["xyz"], atol=1e-12)
        assert np.allclose(ours[frame]["rpy"], theirs[frame]["rpy"], atol=1e-12)
        m = ours[frame]["matrix"]
        assert m.shape == (4, 4) and np.allclose(m[:3, 3], ours[frame]["xyz"])


def test_ik_equals_the_cli_including_the_wrist_singularity(cli):
    for q in ([0.3, -1.2, 1.1, -0.4, 0.9, 0.2], [1, -1, 0.3, -1, 0, 1]):
        flange = kinematics.fk(q)["flange"]
        pose = np.concatenate([flange["xyz"], flange["rpy"]])
        ours = kinematics.ik(pose)
        theirs = cli("ik", "--pose", *map(repr, pose.tolist()), "--json")["solutions"]
        assert len(ours) == len(theirs) >= 1
        for a, b in zip(ours, theirs):
            assert np.allclose(a["joints"], b["joints"], atol=1e-12) and a["branch"] == b["branch"]


def test_ik_qp_and_world_to_base():
    q = np.array([0.3, -1.2, 1.1, -0.4, 0.9, 0.2])
    f = kinematics.fk(q)["flange"]
    sol = kinematics.ik_qp(np.concatenate([f["xyz"], f["rpy"]]), q + 0.05)
    assert np.allclose(kinematics.fk(sol)["flange"]["xyz"], f["xyz"], atol=2e-4)
    p = kinematics.world_to_base([0.2, -0.1, 0.62, 0, 0, np.pi / 2], [0.6, 0.1, 0.645])
    assert np.allclose(p, [0.2, -0.4, 0.025], atol=1e-12)
    with pytest.raises(ValueError, match=r"point\[1\]"):
        kinematics.world_to_base(np.zeros(6), [0, np.nan, 0])


def run_baseline(preset, seeds):
    env = fairgrasp.FairGraspEnv(preset=preset)
    policy = fairgrasp.Baseline(preset=preset)
    out = []
    for s in seeds:
        obs, _ = env.reset(seed=s)
        policy.reset(s)
        while True:
            obs, _, te, tr, info = env.step(policy.act(obs))
            if te or tr:
                out.append(info["success"])
                break
    return out


def test_the_residual_wrapper_with_a_zero_policy_is_the_baseline():
    seeds = list(range(100, 120))
    direct = run_baseline("seed", seeds)
    env = fairgrasp.ResidualWrapper(fairgrasp.FairGraspEnv(preset="seed"))
    assert env.observation_space.shape == (fairgrasp.OBS_DIM + 7,)
    wrapped = []
    for s in seeds:
        obs, _ = env.reset(seed=s)
        assert obs.shape == env.observation_space.shape
        while True:
            obs, _, te, tr, info = env.step(np.zeros(7))
            if te or tr:
                wrapped.append(info["success"])
                break
    assert wrapped == direct
    assert sum(direct) >= 19, f"the baseline succeeded on {sum(direct)} of 20 seed scenarios"
