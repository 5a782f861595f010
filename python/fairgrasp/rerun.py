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
  ``/m/wrist_torque/{x,y,z}`` [N·m] (the six-axis wrist sensor, about the flange),
  ``/m/phase`` and ``/m/events`` (text logs: the script's phase when it changes, collisions,
  pushes).

Two timelines: ``step`` (0 = the state after reset) and ``sim_time`` (simulated seconds). Methods
stand side by side along the world's y axis, ``spacing_m`` apart. ``import rerun`` happens only
inside ``save``: ``import fairgrasp`` and ``import fairgrasp.rerun`` work without it.

What is read: ``load_episodes`` takes a regular file of at most ``MAX_REPLAY_BYTES`` (64 MiB;
refused by its size before it is read, and a folder, FIFO or device without a blocking open),
strict UTF-8 JSON, and checks every field ``save`` draws (type, length, finite numbers, ranges).
Anything else is one ``ReplayFileError`` (a ValueError) whose message names the file, the field
and the value; ``python/tests-rerun/test_replay_json_fuzz.py`` holds it to that on arbitrary
bytes and on mutations of a real replay.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import stat
import sys
import tempfile
import zlib

REQUIREMENTS = "scripts/requirements-rerun.txt"
_MISSING = (
    "fairgrasp.rerun needs the Rerun SDK (rerun-sdk 0.41.0): pip install -r "
    f"{REQUIREMENTS} (from the fairgrasp checkout), or run the Rerun suite through "
    "scripts/python-package-test.sh with FAIRGRASP_PY_REQUIREMENTS=" + REQUIREMENTS
)
_JOINTS = ("j1", "j2", "j3", "j4", "j5", "j6")
_FINGERS = (("finger_left_joint", "finger_left"), ("finger_right_joint", "finger_right"))


class ReplayFileError(ValueError):
    """The input is not a fairgrasp replay or trajectory JSON that ``save`` can draw: the message
    names the file (or "the episodes given"), the field and what is wrong with it."""


#: The key that marks a `fairgrasp replay --json` file, and the format version this reader knows
#: (``FORMAT_KEY``/``FORMAT_VERSION`` of ``src/cli/replay/json.rs``).
FORMAT_KEY, FORMAT_VERSION = "fairgrasp_replay_json", 1
#: The largest replay JSON read [bytes], packed and (a ``.json.gz``) unpacked: 64 MiB, about
#: 20 000 recorded steps with their forces (3.3 kB each; two methods on a 360-step place episode
#: are 2.4 MB). A larger file is refused by its size, before it is read. Parsing needs at most
#: about 25 × the bytes read (3.6 × for a real replay), so a load stays under about 1.6 GiB.
MAX_REPLAY_BYTES = 64 * 2**20
#: Methods in one file (``fairgrasp replay --policy`` repeated): each is a robot in the scene.
MAX_METHODS = 32
#: Rows of one method: the reset plus at most 100 000 steps (``task.max_steps``'s bound in
#: ``env/src/config/validate.rs``).
MAX_ROWS = 100_001
#: Bodies per scene and shapes per scene (the FR3 cell has 10 bodies and 12 shapes; the place
#: fixture adds its walls).
MAX_BODIES, MAX_SHAPES = 256, 4096
#: The `step` timeline is a signed 64-bit sequence in Rerun; `sim_time` is stored in signed
#: 64-bit nanoseconds, so at most about 9.2e9 s (bounded here at 1e9 s, 31 years).
MAX_STEP, MAX_TIME_S = 2**63 - 1, 1e9
_ABSENT = object()


def load_episodes(path, *, max_bytes=MAX_REPLAY_BYTES):
    """Reads ``path`` (``fairgrasp replay --json`` output, or a trajectory ``.json`` or gzipped
    ``.json.gz``, told by its gzip header) and checks every field ``save`` draws. Returns the
    replay document as read (``methods``: each ``method``, ``trajectory``, ``contact_forces`` or
    None; ``urdf``: the URDF text or None; ``step_s`` …), a bare trajectory as ``{"methods":
    [{"method": "episode", "trajectory": …, "contact_forces": None}], "urdf": None}``.

    Raises ReplayFileError naming the file and what is wrong, for anything else: a missing file, a
    folder, FIFO or device (never opened for a blocking read), a file over ``max_bytes`` (by its
    size, before reading; a gzip stream unpacking past it, after at most ``max_bytes + 1``
    unpacked bytes), bytes that are not UTF-8 JSON (NaN and Infinity are not JSON numbers;
    nesting deeper than Python's parser goes), and a document without the fields, types, lengths
    and ranges ``save`` needs."""
    data = _read_bounded(path, max_bytes)
    doc = _parse_json(path, data)
    if isinstance(doc, dict) and FORMAT_KEY in doc:
        version = doc[FORMAT_KEY]
        if type(version) is not int or version != FORMAT_VERSION:
            raise ReplayFileError(f"{path}: {FORMAT_KEY} = {_shown(version)}: this reader knows "
                                  f"format {FORMAT_VERSION} (a newer fairgrasp wrote it?)")
    elif isinstance(doc, dict) and isinstance(doc.get("rows"), list):
        doc = {"methods": [{"method": "episode", "trajectory": doc, "contact_forces": None}],
               "urdf": None}
    else:
        raise ReplayFileError(
            f"{path}: neither a `fairgrasp replay --json` file (no `{FORMAT_KEY}` key) "
            "nor a trajectory (no `rows` list)"
        )
    check_episodes(path, doc)
    return doc


def _read_bounded(path, max_bytes):
    """The bytes of the regular file ``path`` (gzip unpacked), at most ``max_bytes``. Opened
    without blocking (a FIFO opens at once) and checked by ``fstat`` before anything is read."""
    if not (type(max_bytes) is int and max_bytes > 0):
        raise ValueError(f"max_bytes = {max_bytes!r}: must be a positive integer [bytes]")
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except FileNotFoundError:
        raise ReplayFileError(f"{path}: no such file") from None
    except (OSError, ValueError, TypeError) as e:
        raise ReplayFileError(f"{path}: cannot open it: {e}") from None
    try:
        info = os.fstat(fd)
        if stat.S_ISDIR(info.st_mode):
            raise ReplayFileError(f"{path}: a folder, not a replay JSON file")
        if not stat.S_ISREG(info.st_mode):
            raise ReplayFileError(f"{path}: not a regular file (a FIFO, socket or device is never read)")
        if info.st_size > max_bytes:
            raise ReplayFileError(f"{path}: {info.st_size} bytes, more than the {max_bytes} bytes "
                                  f"({max_bytes / 2**20:g} MiB) a replay JSON may have "
                                  "(--max-mb, or max_bytes= of load_episodes and save, raises it)")
        with os.fdopen(fd, "rb", closefd=False) as f:
            data = f.read(info.st_size + 1)  # a buffer of the file's size, not of the limit
    except OSError as e:
        raise ReplayFileError(f"{path}: reading it failed: {e}") from None
    finally:
        os.close(fd)
    if len(data) > info.st_size:
        raise ReplayFileError(f"{path}: grew while it was read (is it still being written?)")
    return _gunzip(path, data, max_bytes) if data[:2] == b"\x1f\x8b" else data


def _gunzip(path, packed, max_bytes):
    """``packed`` (one gzip stream) unpacked, refused past ``max_bytes`` unpacked bytes. A first
    pass counts the unpacked bytes in 1 MiB pieces it drops, so a gzip bomb costs no memory; the
    second unpacks into one buffer of the counted size."""
    stream, rest, size = zlib.decompressobj(16 + zlib.MAX_WBITS), packed, 0
    try:
        while True:
            piece = stream.decompress(rest, 2**20)
            size += len(piece)
            if size > max_bytes:
                raise ReplayFileError(f"{path}: its JSON is over the {max_bytes} bytes a replay "
                                      "JSON may have, unpacked")
            rest = stream.unconsumed_tail
            if stream.eof or not (piece or rest):
                break
    except zlib.error as e:
        raise ReplayFileError(f"{path}: starts as gzip but does not unpack: {e}") from None
    if not stream.eof:
        raise ReplayFileError(f"{path}: its gzip stream is cut short (a truncated file)")
    if stream.unused_data:
        raise ReplayFileError(f"{path}: {len(stream.unused_data)} bytes follow its gzip stream")
    return zlib.decompress(packed, 16 + zlib.MAX_WBITS, max(size, 1))


def _parse_json(path, data):
    """``data`` as strict JSON (UTF-8; NaN and Infinity refused, as serde_json refuses them)."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise ReplayFileError(f"{path}: not UTF-8 text (byte {e.start}: {e.reason})") from None
    try:
        return json.loads(text, parse_constant=_not_a_json_number)
    except RecursionError:
        raise ReplayFileError(f"{path}: not JSON this reader takes: nested deeper than Python's "
                              "JSON parser goes") from None
    except MemoryError:
        raise ReplayFileError(f"{path}: too large to parse in this process's memory") from None
    except ValueError as e:  # json.JSONDecodeError, an integer of more than 4 300 digits, NaN
        raise ReplayFileError(f"{path}: not JSON: {e}") from None


def _not_a_json_number(name):
    raise ValueError(f"{name} is not a JSON number")


def check_episodes(label, episodes):
    """Raises ReplayFileError (naming ``label``, the field and the value) unless ``episodes`` is
    a dict with a ``urdf`` (text or None) and ``methods``: 1 to MAX_METHODS entries with distinct
    entity names, each with rows and optional forces that hold every field ``save`` draws, of the
    right type, length and range (numbers finite)."""
    f = _Fields(label)
    if not isinstance(episodes, dict):
        f.refuse("the document", f"not an object but {_shown(episodes)}")
    urdf = episodes.get("urdf")
    if urdf is not None:
        f.string("urdf", urdf)
    methods = episodes.get("methods", _ABSENT)
    f.items("methods", methods, 1, MAX_METHODS)
    seen = {}
    for i, m in enumerate(methods):
        _check_method(f, f"methods[{i}]", m)
        name = entity_name(m["method"])
        if name in seen:
            f.refuse(f"methods[{i}].method", f"{_shown(m['method'])} has the entity name "
                     f"`{name}` of methods[{seen[name]}]: give the methods distinct names")
        seen[name] = i


class _Fields:
    """Type and range checks of one file's values; each refusal names the file, the field (its
    path in the document) and the value."""

    def __init__(self, label):
        self.label = label

    def refuse(self, where, what):
        raise ReplayFileError(f"{self.label}: {where}: {what}")

    def object(self, where, value):
        if not isinstance(value, dict):
            self.refuse(where, "missing" if value is _ABSENT else f"not an object but {_shown(value)}")
        return value

    def number(self, where, value, low=-math.inf, high=math.inf, unit=""):
        """A finite number (not a boolean) in [low, high]."""
        if value is _ABSENT:
            self.refuse(where, "missing")
        if type(value) not in (int, float) or not math.isfinite(value) or not low <= value <= high:
            bounds = "" if (low, high) == (-math.inf, math.inf) else f" in [{low:g}, {high:g}]"
            self.refuse(where, f"{_shown(value)}: expected a finite number{bounds}{unit}")
        return value

    def integer(self, where, value, low, high):
        if type(value) is not int or not low <= value <= high:
            self.refuse(where, "missing" if value is _ABSENT else
                        f"{_shown(value)}: expected an integer in [{low}, {high}]")
        return value

    def numbers(self, where, value, n, low=-math.inf, high=math.inf, unit=""):
        """A list of ``n`` finite numbers, each in [low, high]."""
        if not isinstance(value, list) or len(value) != n:
            self.refuse(where, "missing" if value is _ABSENT else
                        f"{_shown(value)}: expected a list of {n} finite numbers{unit}")
        for k, x in enumerate(value):
            self.number(f"{where}[{k}]", x, low, high, unit)
        return value

    def string(self, where, value):
        """Text that encodes as UTF-8 (no lone surrogates, which JSON escapes can make)."""
        if not isinstance(value, str):
            self.refuse(where, "missing" if value is _ABSENT else f"not text but {_shown(value)}")
        try:
            value.encode("utf-8")
        except UnicodeEncodeError:
            self.refuse(where, f"{_shown(value)}: holds a lone surrogate, not text")
        return value

    def items(self, where, value, low, high):
        """A list of ``low`` to ``high`` entries."""
        if not isinstance(value, list) or not low <= len(value) <= high:
            got = "missing" if value is _ABSENT else (
                f"{len(value)} entries" if isinstance(value, list) else _shown(value))
            self.refuse(where, f"expected a list of {low}–{high} entries, got {got}")
        return value


def _shown(value, width=60):
    """``value``'s repr, cut to ``width`` characters (a refused value may be huge)."""
    text = repr(value)
    return text if len(text) <= width else text[: width - 1] + "…"


def _check_method(f, where, m):
    """One method: its name, its trajectory's scene and rows, its forces (None or one per row)."""
    f.object(where, m)
    f.string(f"{where}.method", m.get("method", _ABSENT))
    t = f.object(f"{where}.trajectory", m.get("trajectory", _ABSENT))
    n_bodies = _check_scene(f, f"{where}.trajectory.scene", t.get("scene"))
    rows = f.items(f"{where}.trajectory.rows", t.get("rows", _ABSENT), 1, MAX_ROWS)
    for k, row in enumerate(rows):
        _check_row(f, f"{where}.trajectory.rows[{k}]", row, n_bodies)
    forces = m.get("contact_forces")
    if forces is None:
        return
    if not isinstance(forces, list) or len(forces) != len(rows):
        got = f"{len(forces)} entries" if isinstance(forces, list) else _shown(forces)
        f.refuse(f"{where}.contact_forces", f"{got} for {len(rows)} rows: expected one per row")
    for k, step in enumerate(forces):
        at = f"{where}.contact_forces[{k}]"
        f.object(at, step)
        f.numbers(f"{at}.pad_cube_n", step.get("pad_cube_n", _ABSENT), 2, unit=" [N]")
        f.number(f"{at}.robot_strongest_n", step.get("robot_strongest_n", _ABSENT), unit=" [N]")
        f.numbers(f"{at}.wrist_n", step.get("wrist_n", _ABSENT), 3, unit=" [N]")
        if "wrist_nm" in step:  # files written before the six-axis sensor have none
            f.numbers(f"{at}.wrist_nm", step["wrist_nm"], 3, unit=" [N·m]")


def _check_scene(f, where, scene):
    """The scene ``save`` draws (optional, as in older files); returns its number of bodies."""
    if scene is None:
        return 0
    f.object(where, scene)
    if "base_in_world" in scene:
        f.numbers(f"{where}.base_in_world", scene["base_in_world"], 7)
    if "cube_size" in scene:
        f.number(f"{where}.cube_size", scene["cube_size"], 0, 10, " [m]")
    if scene.get("table_in_world") is not None:
        _check_box(f, f"{where}.table_in_world", scene["table_in_world"])
    bodies = f.items(f"{where}.bodies", scene.get("bodies", []), 0, MAX_BODIES)
    for k, name in enumerate(bodies):
        f.string(f"{where}.bodies[{k}]", name)
    for k, shape in enumerate(f.items(f"{where}.shapes", scene.get("shapes", []), 0, MAX_SHAPES)):
        at = f"{where}.shapes[{k}]"
        f.object(at, shape)
        f.integer(f"{at}.body", shape.get("body", _ABSENT), 0, len(bodies) - 1)
        if f.string(f"{at}.kind", shape.get("kind", _ABSENT)) == "box":
            _check_box(f, at, shape)
    return len(bodies)


def _check_box(f, where, box):
    """A box: its ``centre`` and non-negative ``half_extents`` [m]."""
    f.object(where, box)
    f.numbers(f"{where}.centre", box.get("centre", _ABSENT), 3, unit=" [m]")
    f.numbers(f"{where}.half_extents", box.get("half_extents", _ABSENT), 3, 0, math.inf, " [m]")


def _check_row(f, where, row, n_bodies):
    """One recorded step: the fields every row has, and the optional ones when present."""
    f.object(where, row)
    f.integer(f"{where}.step", row.get("step", _ABSENT), 0, MAX_STEP)
    f.number(f"{where}.time_s", row.get("time_s", _ABSENT), 0, MAX_TIME_S, " [s]")
    f.numbers(f"{where}.joints", row.get("joints", _ABSENT), 6, unit=" [rad]")
    f.numbers(f"{where}.tcp_xyz", row.get("tcp_xyz", _ABSENT), 3, unit=" [m]")
    f.numbers(f"{where}.object_xyz", row.get("object_xyz", _ABSENT), 3, unit=" [m]")
    f.number(f"{where}.reward", row.get("reward", _ABSENT))
    if row.get("object_quat_xyzw") is not None:
        f.numbers(f"{where}.object_quat_xyzw", row["object_quat_xyzw"], 4)
    poses = f.items(f"{where}.bodies", row.get("bodies", []), n_bodies, n_bodies)
    for k, pose in enumerate(poses):
        f.numbers(f"{where}.bodies[{k}]", pose, 7)
    contact = row.get("pad_contact")
    if contact is not None and (not isinstance(contact, list) or len(contact) != 2
                                or not all(type(c) is bool for c in contact)):
        f.refuse(f"{where}.pad_contact", f"{_shown(contact)}: expected [left, right] booleans")
    if row.get("phase") is not None:
        f.string(f"{where}.phase", row["phase"])
    for k, event in enumerate(f.items(f"{where}.events", row.get("events") or [], 0, 10_000)):
        f.string(f"{where}.events[{k}]", event)


def _rerun():
    """The ``rerun`` module, or an ImportError saying how to install it."""
    try:
        import rerun  # noqa: PLC0415 (optional dependency)
        import rerun.urdf  # noqa: F401,PLC0415
    except ImportError as e:
        raise ImportError(_MISSING) from e
    return rerun


def entity_name(method):
    """A method's name as one entity path part: lower case, runs of other characters as ``_``
    (``scripted baseline`` → ``scripted_baseline``)."""
    return re.sub(r"[^a-z0-9]+", "_", method.lower()).strip("_") or "method"


def save(source, rrd, *, urdf=None, spacing_m=1.6, application_id="fairgrasp",
         max_bytes=MAX_REPLAY_BYTES):
    """Writes ``source`` (a path, read by ``load_episodes`` with ``max_bytes``, or a dict as it
    returns) as a Rerun recording at ``rrd`` (atomically: a temporary file in the same folder,
    then renamed). ``urdf``: the robot's URDF file (default: the one the JSON carries, else this
    checkout's ``assets/fr3.urdf``). ``spacing_m``: distance between the methods' cells along
    world y [m]. Returns a summary: ``{"methods": [(entity name, first step, last step, last
    sim_time [s])], "rrd": path}``. Bad input raises ReplayFileError (a ValueError) naming the
    file; nothing is written then."""
    if not (type(spacing_m) in (int, float) and math.isfinite(spacing_m) and spacing_m >= 0):
        raise ValueError(f"spacing_m = {spacing_m!r}: must be a finite number >= 0 [m]")
    rr = _rerun()
    label = "the episodes given" if isinstance(source, dict) else source
    if isinstance(source, dict):
        doc = source
        check_episodes(label, doc)
    else:
        doc = load_episodes(source, max_bytes=max_bytes)
    if urdf is not None:
        _read_bounded(urdf, MAX_REPLAY_BYTES)  # a regular file (a FIFO would block Rerun's loader)
    names = [entity_name(m["method"]) for m in doc["methods"]]
    folder = os.path.dirname(os.path.abspath(rrd))
    os.makedirs(folder, exist_ok=True)
    with tempfile.TemporaryDirectory() as scratch:
        urdf_path = urdf or _urdf_file(doc, scratch)
        trees = [_urdf_tree(rr, urdf_path, name, urdf or label) for name in names]
        rec = rr.RecordingStream(application_id)
        rec.set_log_time_enabled(False)
        fd, tmp = tempfile.mkstemp(suffix=".rrd.tmp", dir=folder)
        os.close(fd)
        try:
            rec.save(tmp, default_blueprint=_blueprint(names, spacing_m))
            summary = [
                _log_method(rr, rec, name, m, tree, (0.0, k * spacing_m, 0.0))
                for k, (name, m, tree) in enumerate(zip(names, doc["methods"], trees))
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


def _urdf_tree(rr, urdf_path, name, label):
    """Rerun's URDF tree of ``urdf_path`` for method ``name`` (frames prefixed ``name/``), or
    ReplayFileError naming ``label`` (the JSON that carries the URDF, or the URDF file) when
    Rerun's loader refuses it or it has no root link."""
    try:
        tree = rr.urdf.UrdfTree.from_file_path(
            urdf_path,
            name,
            frame_prefix=f"{name}/",
            static_transform_entity_path=f"/{name}/tf_static",
        )
        tree.root_link().name  # noqa: B018 (raises without one)
    except (RuntimeError, ValueError, AttributeError) as e:
        raise ReplayFileError(f"{label}: urdf: Rerun's URDF loader refuses it: {e}") from None
    return tree


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


def _log_method(rr, rec, name, m, tree, offset):
    """Logs one method's episode under ``/name``; returns (name, first step, last step, last
    sim_time)."""
    t = m["trajectory"]
    rows, scene = t["rows"], t.get("scene") or {}
    base = f"{name}/base_link"
    rec.log(f"/{name}", rr.Transform3D(translation=offset), static=True)
    _log_robot(rr, rec, name, tree, scene)
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


def _log_robot(rr, rec, name, tree, scene):
    """Logs the URDF tree under ``/name/<robot name>`` (frames prefixed ``name/``) and places
    its ``base_link`` in the method's world (``base_in_world``)."""
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
    for axis, value in zip("xyz", forces.get("wrist_nm", ())):
        rec.log(f"/{name}/wrist_torque/{axis}", rr.Scalars(value))


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
    parser.add_argument("--max-mb", type=float, default=MAX_REPLAY_BYTES / 2**20,
                        help="the largest JSON read [MiB] (default 64, about 20 000 steps)")
    a = parser.parse_args(argv)
    if not (math.isfinite(a.max_mb) and 0 < a.max_mb <= 2**20):
        parser.error(f"--max-mb {a.max_mb}: must be in (0, 1048576] MiB")
    try:
        summary = save(a.episode, a.rrd, urdf=a.urdf, spacing_m=a.spacing,
                       max_bytes=max(1, int(a.max_mb * 2**20)))
    except (ImportError, ValueError, OSError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    for name, first, last, seconds in summary["methods"]:
        print(f"{name}: steps {first}–{last} ({seconds:.2f} s simulated)")
    print(f"Written {a.rrd} ({os.path.getsize(a.rrd) // 1024} KB): open it with `rerun {a.rrd}`")
    return 0


if __name__ == "__main__":
    sys.exit(main())
