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


def _rpy_matrix(r, p, y):
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    return np.array([
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ])


def test_calibrate_points_recovers_a_mount_and_refuses_a_line():
    mount = np.array([0.2, -0.1, 0.75, 0.0, 0.1745, 1.5708])
    rng = np.random.default_rng(3)
    base = rng.uniform([0.2, -0.3, 0.0], [0.5, 0.3, 0.3], size=(6, 3))
    world = base @ _rpy_matrix(*mount[3:]).T + mount[:3]
    fit = kinematics.calibrate_points(world, base)
    assert np.allclose(fit["base_in_world"], mount, atol=1e-9)
    assert fit["rms"] < 1e-9 and len(fit["residuals"]) == 6
    line = np.array([[0.3 + 0.05 * k, 0.1, 0.2] for k in range(4)])
    with pytest.raises(ValueError, match="one line"):
        kinematics.calibrate_points(line, line)
    with pytest.raises(ValueError, match="shape"):
        kinematics.calibrate_points(world[:, :2], base)


def test_calibrate_hand_eye_equals_the_cli_on_the_example(cli):
    import csv
    import os

    root = os.path.join(os.path.dirname(__file__), "..", "..")
    path = os.path.join(root, "assets", "calibration", "camera_stations_example.csv")
    with open(path) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    joints = [[np.radians(float(r[f"j{i}_deg"])) for i in range(1, 7)] for r in rows]
    tcp = []
    for q in joints:
        pose = kinematics.fk(q)["tcp"]
        tcp.append(np.concatenate([pose["xyz"], pose["rpy"]]))
    xyz = ("marker_x_m", "marker_y_m", "marker_z_m")
    rpy = ("marker_roll_deg", "marker_pitch_deg", "marker_yaw_deg")
    marker = [[float(r[k]) for k in xyz] + [np.radians(float(r[k])) for k in rpy] for r in rows]
    ours = kinematics.calibrate_hand_eye(np.array(tcp), np.array(marker))
    theirs = cli("calibrate", "hand-eye", path, "--json")
    assert np.allclose(ours["camera_in_base"][:3], theirs["camera_in_base"]["xyz"], atol=1e-9)
    assert np.allclose(ours["camera_in_base"][3:], theirs["camera_in_base"]["rpy"], atol=1e-9)
    assert "Park" in ours["method"]


def test_a_seven_joint_urdf_chain_solves_what_its_fk_gives(tmp_path):
    from pathlib import Path

    urdf = Path(__file__).resolve().parents[2] / "assets" / "seven_joint_arm.urdf"
    chain = kinematics.Chain(urdf)
    assert chain.joint_names == ["a1", "a2", "a3", "a4", "a5", "a6", "a7"] and chain.tip == "tool0"
    lower, upper = chain.limits
    q = np.array([0.3, 0.5, -0.2, -1.1, 0.4, 0.7, 0.1])
    pose = chain.fk(q)
    answer = chain.ik(pose, seed=1)
    assert answer["position_error_m"] <= 1e-4 and answer["orientation_error_rad"] <= 1e-3
    assert np.all(answer["joints"] >= lower) and np.all(answer["joints"] <= upper)
    assert np.allclose(chain.fk(answer["joints"])[:3], pose[:3], atol=1e-4)
    with pytest.raises(ValueError, match="7 movable joints"):
        chain.fk(np.zeros(6))
    with pytest.raises(ValueError, match="did not converge"):
        chain.ik([3.0, 0.0, 0.5, 0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="name a tip link"):
        kinematics.Chain(urdf.parent / "fr3.urdf")
