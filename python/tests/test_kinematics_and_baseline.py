"""FK/IK from Python equal the CLI's --json (the zero residual against the script: test_residual.py)."""

import numpy as np
import pytest

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
