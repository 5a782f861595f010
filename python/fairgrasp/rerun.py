"""Episodes as Rerun recordings (``.rrd``): ``fairgrasp.rerun.save``, ``python -m fairgrasp.rerun``.

    fairgrasp replay --policy open_loop --policy oracle --json episode.json
    python -m fairgrasp.rerun episode.json --rrd episode.rrd
    rerun episode.rrd          # the native viewer; or rerun --web-viewer episode.rrd

The input is what ``fairgrasp replay --json`` writes (one scenario, one or more methods: each
its recorded trajectory and the contact forces of every step, plus the FR3's URDF), or a bare
trajectory JSON (``.json`` or ``.json.gz``, as ``fairgrasp compare`` folders hold), shown as one
method without forces. Why a Python converter and not a Rust flag: the Rerun Rust SDK would add a
large dependency tree to every build of fairgrasp, while the Python SDK (``rerun-sdk``, pinned in
``scripts/requirements-rerun.txt``) is one wheel that users who want Rerun install anyway.

What the recording holds, for method ``m`` (its name as an entity path part):

- ``/m/fairino_fr3``: the FR3 from its URDF (Rerun's URDF loader: the collision capsules and
  boxes, as fairgrasp simulates them; frames named ``m/<link>``, the URDF's fixed transforms on
  ``/m/tf_static``, ``base_link`` placed in the world by ``/m/mount``), each joint's transform per
  step on ``/m/joints/<joint>`` (j1 … j6 from the recorded joints [rad], the fingers' travel [m]
  from their recorded poses);
- ``/m/table`` (in the world), ``/m/cube`` and, for the place task, ``/m/fixture`` (boxes in
  ``base_link``), ``/m/tcp_path`` (the TCP's path so far, a line strip in ``base_link``);
- time series: ``/m/reward``, ``/m/return``, ``/m/pad_contact/{left,right}`` (0/1),
  ``/m/contact_force/{pad_left,pad_right,robot_strongest}`` and ``/m/wrist_force/{x,y,z}`` [N],
  ``/m/phase`` and ``/m/events`` (text logs: the script's phase when it changes, collisions,
  pushes).

Two timelines: ``step`` (0 = the state after reset) and ``sim_time`` (simulated seconds). Methods
stand side by side along the world's y axis, ``spacing_m`` apart. ``import rerun`` happens only
inside ``save``: ``import fairgrasp`` and ``import fairgrasp.rerun`` work without it.
"""

from __future__ import annotations

import argparse
import gzip
import json
import math
import os
import re
import sys
import tempfile

REQUIREMENTS = "scripts/requirements-rerun.txt"
_MISSING = (
    "fairgrasp.rerun needs the Rerun SDK (rerun-sdk 0.41.0): pip install -r "
    f"{REQUIREMENTS} (from the fairgrasp checkout), or run the Rerun suite through "
    "scripts/python-package-test.sh with FAIRGRASP_PY_REQUIREMENTS=" + REQUIREMENTS
)
_JOINTS = ("j1", "j2", "j3", "j4", "j5", "j6")
_FINGERS = (("finger_left_joint", "finger_left"), ("finger_right_joint", "finger_right"))


class ReplayFileError(ValueError):
    """The input file is not a fairgrasp replay or trajectory JSON (the message names it)."""


def _rerun():
    """The ``rerun`` module, or an ImportError saying how to install it."""
    try:
        import rerun  # noqa: PLC0415 (optional dependency)
        import rerun.urdf  # noqa: F401,PLC0415
    except ImportError as e:
        raise ImportError(_MISSING) from e
    return rerun


def load_episodes(path):
    """Reads ``path`` (``fairgrasp replay --json`` output, or a trajectory ``.json``/``.json.gz``)
    as a dict with ``methods`` (each ``method``, ``trajectory``, ``contact_forces`` or None),
    ``urdf`` (the URDF text, or None) and ``step_s``. Raises ReplayFileError on anything else."""
    try:
        opener = gzip.open if str(path).endswith(".gz") else open
        with opener(path, "rt", encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError, EOFError) as e:
        raise ReplayFileError(f"{path}: cannot read it as JSON: {e}") from e
    if isinstance(doc, dict) and "fairgrasp_replay_json" in doc:
        methods = doc.get("methods")
    elif isinstance(doc, dict) and isinstance(doc.get("rows"), list):
        doc = {"methods": [{"method": "episode", "trajectory": doc, "contact_forces": None}]}
        methods = doc["methods"]
    else:
        raise ReplayFileError(
            f"{path}: neither a `fairgrasp replay --json` file (no `fairgrasp_replay_json` key) "
            "nor a trajectory (no `rows` list)"
        )
    _check_methods(path, methods)
    return doc


def _check_methods(label, methods):
    """Raises ReplayFileError (naming ``label``) unless ``methods`` is a non-empty list of
    entries each with a name and rows with the fields ``save`` uses."""
    if not isinstance(methods, list) or not methods:
        raise ReplayFileError(f"{label}: `methods` must be a non-empty list")
    for i, m in enumerate(methods):
        _check_method(label, i, m)


def _check_method(path, i, m):
    """Raises ReplayFileError unless method entry ``i`` has a name and rows with the fields used."""
    if not isinstance(m, dict) or not isinstance(m.get("method"), str):
        raise ReplayFileError(f"{path}: methods[{i}].method: missing or not a string")
    rows = (m.get("trajectory") or {}).get("rows")
    if not isinstance(rows, list) or not rows:
        raise ReplayFileError(f"{path}: methods[{i}].trajectory.rows: missing or empty")
    for key in ("step", "time_s", "joints", "tcp_xyz", "object_xyz", "reward"):
        if key not in rows[0]:
            raise ReplayFileError(f"{path}: methods[{i}].trajectory.rows[0]: no `{key}`")
    forces = m.get("contact_forces")
    if forces is not None and len(forces) != len(rows):
        raise ReplayFileError(
            f"{path}: methods[{i}].contact_forces: {len(forces)} entries for {len(rows)} rows"
        )


def entity_name(method):
    """A method's name as one entity path part: lower case, runs of other characters as ``_``
    (``scripted baseline`` → ``scripted_baseline``)."""
    return re.sub(r"[^a-z0-9]+", "_", method.lower()).strip("_") or "method"


def save(source, rrd, *, urdf=None, spacing_m=1.6, application_id="fairgrasp"):
    """Writes ``source`` (a path, or the dict ``load_episodes`` returns) as a Rerun recording at
    ``rrd`` (atomically: a temporary file in the same folder, then renamed). ``urdf``: the robot's
    URDF file (default: the one the JSON carries, else this checkout's ``assets/fr3.urdf``).
    ``spacing_m``: distance between the methods' cells along world y [m]. Returns a summary:
    ``{"methods": [(entity name, first step, last step, last sim_time [s])], "rrd": path}``."""
    if not (isinstance(spacing_m, (int, float)) and math.isfinite(spacing_m) and spacing_m >= 0):
        raise ValueError(f"spacing_m = {spacing_m!r}: must be a finite number >= 0 [m]")
    rr = _rerun()
    if isinstance(source, dict):
        doc = source
        _check_methods("the episodes given", doc.get("methods"))
    else:
        doc = load_episodes(source)
    names = [entity_name(m["method"]) for m in doc["methods"]]
    if len(set(names)) != len(names):
        raise ValueError(f"two methods have the same entity name: {names}")
    folder = os.path.dirname(os.path.abspath(rrd))
    os.makedirs(folder, exist_ok=True)
    with tempfile.TemporaryDirectory() as scratch:
        urdf_path = urdf or _urdf_file(doc, scratch)
        rec = rr.RecordingStream(application_id)
        rec.set_log_time_enabled(False)
        fd, tmp = tempfile.mkstemp(suffix=".rrd.tmp", dir=folder)
        os.close(fd)
        try:
            rec.save(tmp, default_blueprint=_blueprint(names, spacing_m))
            summary = [
                _log_method(rr, rec, name, m, urdf_path, (0.0, k * spacing_m, 0.0))
                for k, (name, m) in enumerate(zip(names, doc["methods"]))
            ]
            rec.flush()
            rec.disconnect()
            os.chmod(tmp, 0o644)
            os.replace(tmp, rrd)
        finally:
            if os.path.exists(tmp):
                os.remove(tmp)
    return {"methods": summary, "rrd": str(rrd)}


def _urdf_file(doc, scratch):
    """A URDF file for the loader: the JSON's URDF text written to ``scratch``, else
    ``assets/fr3.urdf`` of this checkout (beside ``python/``) or of the working directory."""
    if doc.get("urdf"):
        path = os.path.join(scratch, "fr3.urdf")
        with open(path, "w", encoding="utf-8") as f:
            f.write(doc["urdf"])
        return path
    here = os.path.dirname(os.path.abspath(__file__))
    for candidate in (os.path.join(here, "..", "..", "assets", "fr3.urdf"), "assets/fr3.urdf"):
        if os.path.isfile(candidate):
            return candidate
    raise FileNotFoundError("no URDF in the JSON and no assets/fr3.urdf found: pass urdf=PATH")


def _blueprint(names, spacing_m):
    """The viewer's layout: the 3D scene on the left, seen from the front right of the cells
    (world z up); reward, contact forces and phases of every method on the right; the `step`
    timeline, paused."""
    import rerun.blueprint as rrb  # noqa: PLC0415

    def each(suffix):
        return [f"/{n}/{suffix}" for n in names]

    middle = 0.5 * (len(names) - 1) * spacing_m
    eye = rrb.EyeControls3D(position=[1.5, middle - 0.8 - 0.5 * len(names), 1.45],
                            look_target=[0.2, middle, 0.6], eye_up=[0.0, 0.0, 1.0])
    return rrb.Blueprint(
        rrb.Horizontal(
            rrb.Spatial3DView(name="cell", origin="/", eye_controls=eye),
            rrb.Vertical(
                rrb.TimeSeriesView(name="reward", contents=each("reward")),
                rrb.TimeSeriesView(name="contact force [N]", contents=each("contact_force/**")),
                rrb.TextLogView(name="phase and events", contents=each("phase") + each("events")),
            ),
            column_shares=[3, 2],
        ),
        rrb.TimePanel(timeline="step", play_state="paused", state="collapsed"),
        collapse_panels=True,
    )


def _log_method(rr, rec, name, m, urdf_path, offset):
    """Logs one method's episode under ``/name``; returns (name, first step, last step, last
    sim_time)."""
    t = m["trajectory"]
    rows, scene = t["rows"], t.get("scene") or {}
    base = f"{name}/base_link"
    rec.log(f"/{name}", rr.Transform3D(translation=offset), static=True)
    tree = _log_robot(rr, rec, name, urdf_path, scene)
    _log_static_scene(rr, rec, name, scene, rows[0], base)
    rec.log(f"/{name}/cube", rr.CoordinateFrame(base), static=True)
    rec.log(f"/{name}/tcp_path", rr.CoordinateFrame(base), static=True)
    path, ret, phase = [], 0.0, None
    forces = m.get("contact_forces")
    for i, row in enumerate(rows):
        rec.set_time("step", sequence=int(row["step"]))
        rec.set_time("sim_time", duration=float(row["time_s"]))
        _log_joints(rec, tree, name, row, scene)
        rec.log(f"/{name}/cube", _cube(rr, row, scene))
        path.append(row["tcp_xyz"])
        rec.log(f"/{name}/tcp_path", rr.LineStrips3D([path], radii=0.002, colors=[255, 140, 0]))
        ret += row["reward"]
        _log_series(rr, rec, name, row, ret, forces[i] if forces else None)
        if row.get("phase") and row["phase"] != phase:
            phase = row["phase"]
            rec.log(f"/{name}/phase", rr.TextLog(f"{m['method']}: {phase}", level="INFO"))
        for event in row.get("events") or []:
            rec.log(f"/{name}/events", rr.TextLog(f"{m['method']}: {event}", level="WARN"))
    return (name, int(rows[0]["step"]), int(rows[-1]["step"]), float(rows[-1]["time_s"]))


def _log_robot(rr, rec, name, urdf_path, scene):
    """Logs the URDF under ``/name/<robot name>`` (frames prefixed ``name/``) and places its
    ``base_link`` in the method's world (``base_in_world``)."""
    tree = rr.urdf.UrdfTree.from_file_path(
        urdf_path,
        name,
        frame_prefix=f"{name}/",
        static_transform_entity_path=f"/{name}/tf_static",
    )
    tree.log_urdf_to_recording(rec)
    pose = scene.get("base_in_world") or [0, 0, 0, 0, 0, 0, 1]
    rec.log(
        f"/{name}/mount",
        rr.Transform3D(
            translation=pose[:3],
            quaternion=rr.Quaternion(xyzw=pose[3:]),
            parent_frame=f"tf#/{name}",
            child_frame=f"{name}/{tree.root_link().name}",
        ),
        static=True,
    )
    return tree


def _log_static_scene(rr, rec, name, scene, first, base):
    """The table (in the method's world) and the fixture's walls (in its own frame, placed in
    ``base_link`` at its first recorded pose), logged once."""
    table = scene.get("table_in_world")
    if table:
        rec.log(
            f"/{name}/table",
            rr.Boxes3D(centers=[table["centre"]], half_sizes=[table["half_extents"]],
                       colors=[150, 120, 90], fill_mode="solid"),
            static=True,
        )
    bodies = scene.get("bodies") or []
    if "fixture" not in bodies or not first.get("bodies"):
        return
    k = bodies.index("fixture")
    pose = first["bodies"][k]
    walls = [s for s in scene.get("shapes") or [] if s.get("body") == k and s.get("kind") == "box"]
    rec.log(
        f"/{name}/fixture",
        rr.Transform3D(translation=pose[:3], quaternion=rr.Quaternion(xyzw=pose[3:]),
                       parent_frame=base, child_frame=f"{name}/fixture"),
        rr.CoordinateFrame(f"{name}/fixture"),
        rr.Boxes3D(centers=[w["centre"] for w in walls],
                   half_sizes=[w["half_extents"] for w in walls],
                   colors=[90, 90, 200], fill_mode="solid"),
        static=True,
    )


def _log_joints(rec, tree, name, row, scene):
    """Each joint's transform at ``row``: j1 … j6 from the joints, the fingers from their poses."""
    values = dict(zip(_JOINTS, row["joints"]))
    values.update(_finger_travel(tree, row, scene))
    for joint, value in values.items():
        j = tree.get_joint_by_name(joint)
        if j is not None:
            transform = j.compute_transform(float(value), clamp=False)
            rec.log(f"/{name}/joints/{joint}", transform)


def _finger_travel(tree, row, scene):
    """Each finger's travel [m] (0 = open) from its recorded pose relative to the palm: the
    offset from the joint's origin along its axis (the URDF's prismatic finger joints)."""
    bodies = scene.get("bodies") or []
    poses = row.get("bodies") or []
    if "palm" not in bodies or len(poses) != len(bodies):
        return {}
    palm = poses[bodies.index("palm")]
    out = {}
    for joint, link in _FINGERS:
        j = tree.get_joint_by_name(joint)
        if j is None or link not in bodies:
            continue
        finger = poses[bodies.index(link)]
        d = [finger[i] - palm[i] for i in range(3)]
        local = _rotate(_conjugate(palm[3:]), d)
        out[joint] = sum((local[i] - j.origin_xyz[i]) * j.axis[i] for i in range(3))
    return out


def _cube(rr, row, scene):
    """The cube at ``row``: a box of the scene's edge length at its recorded pose (base_link)."""
    half = 0.5 * float(scene.get("cube_size", 0.05))
    q = row.get("object_quat_xyzw") or [0, 0, 0, 1]
    return rr.Boxes3D(centers=[row["object_xyz"]], half_sizes=[[half, half, half]],
                      quaternions=[rr.Quaternion(xyzw=q)], colors=[200, 40, 40],
                      fill_mode="solid")


def _log_series(rr, rec, name, row, ret, forces):
    """Reward, return, pad contacts and (when measured) the contact and wrist forces at ``row``."""
    rec.log(f"/{name}/reward", rr.Scalars(row["reward"]))
    rec.log(f"/{name}/return", rr.Scalars(ret))
    for side, touching in zip(("left", "right"), row.get("pad_contact") or [False, False]):
        rec.log(f"/{name}/pad_contact/{side}", rr.Scalars(1.0 if touching else 0.0))
    if forces is None:
        return
    pads = forces["pad_cube_n"]
    rec.log(f"/{name}/contact_force/pad_left", rr.Scalars(pads[0]))
    rec.log(f"/{name}/contact_force/pad_right", rr.Scalars(pads[1]))
    rec.log(f"/{name}/contact_force/robot_strongest", rr.Scalars(forces["robot_strongest_n"]))
    for axis, value in zip("xyz", forces["wrist_n"]):
        rec.log(f"/{name}/wrist_force/{axis}", rr.Scalars(value))


def _conjugate(q):
    return [-q[0], -q[1], -q[2], q[3]]


def _rotate(q, v):
    """``v`` rotated by the unit quaternion ``q`` = [x, y, z, w]."""
    x, y, z, w = q
    # t = 2 q_vec × v; v' = v + w t + q_vec × t
    t = [2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])]
    c = [y * t[2] - z * t[1], z * t[0] - x * t[2], x * t[1] - y * t[0]]
    return [v[i] + w * t[i] + c[i] for i in range(3)]


def main(argv=None):
    """``python -m fairgrasp.rerun EPISODE.json --rrd FILE.rrd [--urdf FILE] [--spacing M]``."""
    parser = argparse.ArgumentParser(
        prog="python -m fairgrasp.rerun",
        description="Write a `fairgrasp replay --json` file (or a trajectory JSON) as a Rerun .rrd",
    )
    parser.add_argument("episode",
                        help="fairgrasp replay --json output, or a trajectory .json[.gz]")
    parser.add_argument("--rrd", required=True, help="the .rrd file to write")
    parser.add_argument("--urdf",
                        help="robot URDF (default: the one in the JSON, else assets/fr3.urdf)")
    parser.add_argument("--spacing", type=float, default=1.6,
                        help="distance between the methods' cells along world y [m] (default 1.6)")
    a = parser.parse_args(argv)
    try:
        summary = save(a.episode, a.rrd, urdf=a.urdf, spacing_m=a.spacing)
    except (ImportError, ValueError, OSError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    for name, first, last, seconds in summary["methods"]:
        print(f"{name}: steps {first}–{last} ({seconds:.2f} s simulated)")
    print(f"Written {a.rrd} ({os.path.getsize(a.rrd) // 1024} KB): open it with `rerun {a.rrd}`")
    return 0


if __name__ == "__main__":
    sys.exit(main())
