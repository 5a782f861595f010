"""The FR3/FR5 kinematics and frame calibration, NumPy in and out (the Rust library the CLI
uses).

Poses are ``[x, y, z, roll, pitch, yaw]`` in base_link (metres, URDF fixed-axis radians), as
``fairgrasp fk/ik --json`` print them; frames are ``"tool0"`` (the flange) or ``"tcp"``.
"""

import numpy as np

from . import _native


def _floats(values, what):
    """``values`` as a float64 array; anything else is a ValueError that quotes at most 60
    characters of it (numpy's own message quotes a string argument whole)."""
    try:
        return np.ascontiguousarray(values, dtype=np.float64)
    except (TypeError, ValueError, OverflowError):
        shown = repr(values)
        shown = shown if len(shown) <= 60 else f"{shown[:60]}… ({len(shown)} characters)"
        raise ValueError(f"{what} must be numbers, got {type(values).__name__} {shown}") from None


def _vec(values, n, what):
    a = _floats(values, what).reshape(-1)
    if a.shape != (n,):
        raise ValueError(f"{what} has {a.size} values, expected {n}")
    return a


def fk(joints, model="fr3"):
    """Forward kinematics: ``{"flange": {...}, "tcp": {...}, "in_limits": bool}``, each frame
    with ``xyz``, ``rpy`` and its 4×4 ``matrix`` in base_link."""
    return _native.fk(_vec(joints, 6, "joints"), model)


def ik(pose, frame="tool0", current=None, model="fr3"):
    """Every closed-form IK branch for ``pose``: a list of ``{"joints", "in_limits", "branch"}``
    (empty when out of reach). ``current`` sets θ6 at a wrist singularity."""
    current = None if current is None else _vec(current, 6, "current")
    return _native.ik(_vec(pose, 6, "pose"), frame, current, model)


def ik_qp(pose, start, frame="tool0", seed=0, model="fr3"):
    """The clarabel QP IK from ``start`` (joint limits respected): the joints, or ValueError."""
    return _native.ik_qp(_vec(pose, 6, "pose"), _vec(start, 6, "start"), frame, seed, model)


class Chain:
    """Any serial arm read from a URDF (N movable joints): ``fk(q)`` and ``ik(pose)``, the chain
    IK of ``fairgrasp ik --urdf`` (damped QP steps within the joint limits, seeded random
    restarts). ``tip`` names the chain's last link where the URDF branches (e.g. ``"tool0"`` in
    the FR3's URDF, whose gripper has fingers). Poses are ``[x, y, z, roll, pitch, yaw]`` in the
    URDF's root link."""

    def __init__(self, urdf, tip=None):
        self._native = _native.Chain(str(urdf), tip)

    @property
    def joint_names(self):
        return self._native.joint_names

    @property
    def limits(self):
        """``(lower, upper)`` arrays, radians or metres per joint."""
        return self._native.limits

    @property
    def tip(self):
        return self._native.tip

    def fk(self, q):
        """The tip's pose ``[x, y, z, roll, pitch, yaw]`` at joints ``q``."""
        return self._native.fk(np.ascontiguousarray(q, dtype=np.float64).reshape(-1))

    def ik(self, pose, start=None, seed=0):
        """Joints placing the tip at ``pose``: ``{"joints", "position_error_m",
        "orientation_error_rad", "iterations", "attempts"}``; ``ValueError`` when it does not
        converge (with the best residual) or a value is wrong."""
        start = None if start is None else np.ascontiguousarray(start, dtype=np.float64).reshape(-1)
        return self._native.ik(_vec(pose, 6, "pose"), start, int(seed))


def world_to_base(base_pose, point):
    """A world point expressed in base_link, given base_link's pose in the world."""
    return _native.world_to_base(_vec(base_pose, 6, "base_pose"), _vec(point, 3, "point"))


def _rows(values, width, what):
    a = _floats(values, what)
    if a.ndim != 2 or a.shape[1] != width:
        raise ValueError(f"{what} has shape {a.shape}, expected (n, {width})")
    return a


def calibrate_points(world_points, base_points, max_residual=0.005):
    """``world ↔ base_link`` from touched points (``fairgrasp calibrate points``): each row of
    ``world_points`` and ``base_points`` ((n, 3), metres) is one point in the two frames.
    Returns ``{"base_in_world": [x, y, z, roll, pitch, yaw], "residuals", "rms", "scale",
    "warnings"}``; too few, collinear or mistyped points raise ValueError naming the problem."""
    return _native.calibrate_points(
        _rows(world_points, 3, "world_points"), _rows(base_points, 3, "base_points"), max_residual
    )


def calibrate_hand_eye(tcp_poses, marker_poses):
    """A fixed camera's pose in base_link (eye-to-hand, Park–Martin; ``fairgrasp calibrate
    hand-eye``) from stations: ``tcp_poses`` (the TCP in base_link) and ``marker_poses`` (the
    marker in the camera), (n, 6) each as ``[x, y, z, roll, pitch, yaw]``. Returns
    ``{"camera_in_base", "marker_in_tcp", "position_residuals", "angle_residuals", "method"}``."""
    return _native.calibrate_hand_eye(
        _rows(tcp_poses, 6, "tcp_poses"), _rows(marker_poses, 6, "marker_poses")
    )
