"""Property tests of the replay JSON loader of fairgrasp.rerun (issue 60, items 5 and 6): arbitrary
bytes, byte mutations and JSON mutations of a real `fairgrasp replay --json` file, truncated,
huge, gzipped and not-a-file inputs. Each case either loads or raises ReplayFileError whose
message starts with the file's name and says what is wrong; never another exception, within
CASE_S seconds, with a tracemalloc peak under MEMORY_FACTOR × its bytes + MEMORY_SLACK. A
mutated file that loads is then written as a .rrd, or refused the same way.

Hypothesis runs derandomized (the same cases on every run, no example database), so CI is
deterministic: EXAMPLES cases per property (730 in all), plus about 280 fixed cases (every
truncation step, damaged URDFs, huge and not-a-file inputs): about 70 s on 2 shared cores.

Needs the venv of scripts/requirements-rerun.txt and FAIRGRASP_BIN (set by tests/rerun_file.rs)."""

import contextlib
import gzip
import json
import os
import signal
import subprocess
import sys
import time
import tracemalloc

import pytest
from hypothesis import HealthCheck, currently_in_test_context, event, given, settings
from hypothesis import strategies as st

import fairgrasp.rerun as fr

#: Seconds one load may take (a real replay loads in about 6 ms).
CASE_S = 5.0
#: Parsing JSON takes at most about 25 × its bytes in Python objects (empty lists and objects;
#: 3.6 × for a real replay): the bound asserted on every case's tracemalloc peak, plus a slack
#: for the exception and its message.
MEMORY_FACTOR, MEMORY_SLACK = 32, 4 * 2**20
EXAMPLES = {"bytes": 300, "byte_mutations": 200, "json_mutations": 200, "save": 30}


def _settings(examples):
    return settings(max_examples=examples, derandomize=True, database=None, deadline=None,
                    print_blob=False,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                           HealthCheck.large_base_example])


class Replay:
    """A real replay file: its ``path``, its ``bytes`` and a scratch ``folder`` for the cases
    (a short repr: Hypothesis prints it with a failing case)."""

    def __init__(self, path, data, folder):
        self.path, self.bytes, self.folder = path, data, folder

    def __repr__(self):
        return f"Replay({self.path}, {len(self.bytes)} bytes)"


@pytest.fixture(scope="module")
def replay(tmp_path_factory):
    """A real `fairgrasp replay --json` file: open_loop and oracle on the sector preset's
    scenario 0."""
    folder = tmp_path_factory.mktemp("fuzz")
    path = folder / "episode.json"
    subprocess.run([os.environ["FAIRGRASP_BIN"], "replay", "--policy", "open_loop", "--policy",
                    "oracle", "--json", str(path)], check=True, capture_output=True)
    return Replay(path, path.read_bytes(), folder)


class CaseTimeout(BaseException):
    """A case ran past its time bound (a BaseException, so no `except Exception` swallows it)."""


@contextlib.contextmanager
def time_bound(seconds):
    """Raises CaseTimeout in this thread after ``seconds`` (SIGALRM)."""
    def expire(signum, frame):
        raise CaseTimeout(f"over {seconds} s")
    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def load_or_refuse(path, size, **kwargs):
    """``fr.load_episodes(path)`` as (the document or None, the refusal's message or None, the
    tracemalloc peak [bytes]): a
    refusal must be a ReplayFileError naming ``path`` first, then what is wrong; the load must end
    within CASE_S s and its tracemalloc peak stay under the bound for ``size`` bytes read."""
    tracemalloc.start()
    start = time.perf_counter()
    doc, message = None, None
    try:
        with time_bound(2 * CASE_S):
            try:
                doc = fr.load_episodes(path, **kwargs)
            except fr.ReplayFileError as e:
                message = str(e)
        elapsed = time.perf_counter() - start
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert elapsed < CASE_S, f"{path}: {elapsed:.1f} s"
    assert peak <= MEMORY_FACTOR * size + MEMORY_SLACK, f"{path}: {peak} B for {size} B read"
    if message is not None:
        assert message.startswith(f"{path}: ") and len(message) > len(f"{path}: ") + 5, message
    if currently_in_test_context():  # pytest --hypothesis-show-statistics counts them
        event("refused" if message else "loaded")
    return doc, message, peak


def write_case(folder, data, name="case.json"):
    path = folder / name
    path.write_bytes(data)
    return path


# ----------------------------------------------------------------------------------------------
# Arbitrary bytes.

def _prefixed(prefix):
    return st.binary(max_size=2048).map(lambda b: prefix + b)


ARBITRARY = st.one_of(
    st.binary(max_size=4096),
    _prefixed(b"\x1f\x8b"),  # the gzip header, then anything
    st.binary(max_size=2048).map(gzip.compress),  # gzip of anything
    _prefixed(b'{"fairgrasp_replay_json": 1, "methods": '),
    _prefixed(b'{"rows": ['),
    st.text(alphabet='{}[]:,"0123456789.eE+-ntrufalsNIiy \\', max_size=2048).map(str.encode),
)


@_settings(EXAMPLES["bytes"])
@given(data=ARBITRARY)
def test_arbitrary_bytes_load_or_are_refused_naming_the_file(replay, data):
    folder = replay.folder
    doc, _, _ = load_or_refuse(write_case(folder, data), len(data))
    if doc is not None:  # the few that load hold every field save draws
        fr.check_episodes("loaded", doc)


# ----------------------------------------------------------------------------------------------
# Byte mutations of a real file: bits flipped, cut, a slice repeated, a range deleted, structural
# characters and odd numbers put in.

TOKENS = [b"{", b"}", b"[", b"]", b":", b",", b'"', b"\\", b"NaN", b"Infinity", b"-Infinity",
          b"1e999", b"-1e400", b"1e308", b"null", b"true", b'""', b"[]", b"{}", b"\xff", b"\x00",
          b"9" * 5000, b"[" * 50_000]


@st.composite
def byte_mutations(draw, size):
    """1–4 edits of a ``size``-byte file, as (kind, arguments)."""
    position = st.integers(0, size - 1)
    edit = st.one_of(
        st.tuples(st.just("flip"), position, st.integers(0, 7)),
        st.tuples(st.just("cut"), position),
        st.tuples(st.just("repeat"), position, st.integers(1, 4096), st.integers(1, 50)),
        st.tuples(st.just("delete"), position, st.integers(1, 4096)),
        st.tuples(st.just("insert"), position, st.sampled_from(TOKENS)),
    )
    return draw(st.lists(edit, min_size=1, max_size=4))


def mutate_bytes(data, edits):
    data = bytearray(data)
    for kind, at, *args in edits:
        at = min(at, max(len(data) - 1, 0))
        if kind == "flip" and data:
            data[at] ^= 1 << args[0]
        elif kind == "cut":
            del data[at:]
        elif kind == "repeat":
            data[at:at] = data[at:at + args[0]] * args[1]
        elif kind == "delete":
            del data[at:at + args[0]]
        elif kind == "insert":
            data[at:at] = args[0]
    return bytes(data)


@_settings(EXAMPLES["byte_mutations"])
@given(edits=st.data())
def test_byte_mutations_of_a_real_replay_load_or_are_refused_naming_the_file(replay, edits):
    real, folder = replay.bytes, replay.folder
    data = mutate_bytes(real, edits.draw(byte_mutations(len(real))))
    doc, _, _ = load_or_refuse(write_case(folder, data), len(data))
    if doc is not None:
        fr.check_episodes("loaded", doc)


# ----------------------------------------------------------------------------------------------
# JSON mutations: one value anywhere in the document replaced by another type, a non-finite or
# huge number, deep nesting; a key deleted; a list emptied, cut or repeated; a string cut.

DEEP = "@@deep@@"
REPLACEMENTS = [float("nan"), float("inf"), float("-inf"), 1e308, -1e308, 10**30, 2**63, -1, 0,
                0.5, True, False, None, "", "x", "\ud800", "é" * 3, [], {}, [1.0, 2.0, 3.0],
                [[0.0] * 7], {"rows": []}, DEEP]


@st.composite
def json_mutation(draw, doc):
    """A path into ``doc`` (a walk of 0–9 steps) and what is done there."""
    path, node = [], doc
    for _ in range(draw(st.integers(0, 9))):
        if isinstance(node, dict) and node:
            key = draw(st.sampled_from(sorted(node)))
        elif isinstance(node, list) and node:
            key = draw(st.integers(0, len(node) - 1))
        else:
            break
        path.append(key)
        node = node[key]
    action = draw(st.sampled_from(["replace", "delete", "empty", "cut", "repeat", "cut_string"]))
    value = draw(st.sampled_from(REPLACEMENTS)) if action == "replace" else None
    return path, action, value, draw(st.integers(0, 400))


def mutate_json(doc, path, action, value, n):
    """Applies the mutation to ``doc`` in place; returns the new root (a replaced root)."""
    if not path:
        return value if action == "replace" else doc
    parent = doc
    for key in path[:-1]:
        parent = parent[key]
    key, node = path[-1], parent[path[-1]]
    if action == "replace":
        parent[key] = value
    elif action == "delete":
        del parent[key]
    elif action == "empty" and isinstance(node, (list, dict, str)):
        parent[key] = type(node)()
    elif action == "cut" and isinstance(node, list):
        parent[key] = node[: n % (len(node) + 1)]
    elif action == "repeat" and isinstance(node, list):
        parent[key] = node * (1 + n % 3)
    elif action == "cut_string" and isinstance(node, str):
        parent[key] = node[: n * len(node) // 400]
    return doc


def dump_with_deep_nesting(doc):
    """``doc`` as JSON (NaN and Infinity as Python writes them), DEEP as 100 000 nested lists."""
    text = json.dumps(doc, allow_nan=True)
    return text.replace(json.dumps(DEEP), "[" * 100_000 + "]" * 100_000).encode("utf-8",
                                                                                  "surrogatepass")


@_settings(EXAMPLES["json_mutations"])
@given(data=st.data())
def test_json_mutations_of_a_real_replay_load_or_are_refused_naming_the_field(replay, data):
    real, folder = replay.bytes, replay.folder
    doc = mutate_json(json.loads(real), *data.draw(json_mutation(json.loads(real))))
    encoded = dump_with_deep_nesting(doc)
    loaded, _, _ = load_or_refuse(write_case(folder, encoded), len(encoded))
    if loaded is not None:
        fr.check_episodes("loaded", loaded)
    # The same document given to save as a dict (NaN and infinity reach the checks this way).
    if DEEP not in json.dumps(doc):
        try:
            fr.check_episodes("the episodes given", doc)
        except fr.ReplayFileError as e:
            assert str(e).startswith("the episodes given: "), str(e)


@_settings(EXAMPLES["save"])
@given(data=st.data())
def test_a_mutated_replay_that_loads_is_written_as_rrd_or_refused(replay, data):
    real, folder = replay.bytes, replay.folder
    doc = mutate_json(json.loads(real), *data.draw(json_mutation(json.loads(real))))
    path = write_case(folder, dump_with_deep_nesting(doc), "save_case.json")
    rrd = folder / "save_case.rrd"
    if rrd.exists():
        rrd.unlink()
    try:
        summary = fr.save(path, rrd)
    except fr.ReplayFileError as e:
        assert str(e).startswith(f"{path}: "), str(e)
        assert not rrd.exists()
        event("refused")
    else:
        event("written")
        assert rrd.stat().st_size > 0 and len(summary["methods"]) == len(doc["methods"])
    assert not [f for f in os.listdir(folder) if f.endswith(".rrd.tmp")]


# ----------------------------------------------------------------------------------------------
# Truncated, huge, gzipped and not-a-file inputs.

def test_every_truncation_of_a_real_replay_is_refused_as_not_json(replay):
    path, real, folder = replay.path, replay.bytes, replay.folder
    cuts = sorted(set(range(0, 64)) | set(range(0, len(real), len(real) // 200)))
    for cut in cuts:
        case = write_case(folder, real[:cut])
        with pytest.raises(fr.ReplayFileError, match="not JSON"):
            fr.load_episodes(case)
    assert fr.load_episodes(path)["methods"][0]["method"] == "scripted baseline"


def test_a_200_mb_file_is_refused_by_its_size_before_it_is_read(replay):
    folder = replay.folder
    huge = folder / "huge.json"
    with open(huge, "wb") as f:  # valid-looking JSON, then a 200 MB hole (sparse: no disk used)
        f.write(b'{"fairgrasp_replay_json": 1, "methods": [')
        f.truncate(200 * 10**6)
    tracemalloc.start()
    start = time.perf_counter()
    try:
        with pytest.raises(fr.ReplayFileError) as refused:
            fr.load_episodes(huge)
        assert time.perf_counter() - start < 1.0
        assert tracemalloc.get_traced_memory()[1] < 2**20  # nothing of it was read
    finally:
        tracemalloc.stop()
    assert str(refused.value) == (
        f"{huge}: 200000000 bytes, more than the {fr.MAX_REPLAY_BYTES} bytes (64 MiB) a replay JSON "
        "may have (--max-mb, or max_bytes= of load_episodes and save, raises it)")
    # A lower limit refuses a real replay the same way; a higher one reads it.
    path, real = replay.path, replay.bytes
    with pytest.raises(fr.ReplayFileError, match=f"{len(real)} bytes, more than the 1000 bytes"):
        fr.load_episodes(path, max_bytes=1000)
    assert fr.load_episodes(path, max_bytes=len(real))["methods"]


def test_a_gzip_that_unpacks_past_the_limit_is_refused_within_it(replay):
    folder = replay.folder
    limit = fr.MAX_REPLAY_BYTES
    bomb = gzip.compress(b'{"rows": [' + b"0," * (limit // 2 + 1024) + b"0]}", compresslevel=9)
    path = write_case(folder, bomb, "bomb.json.gz")
    assert len(bomb) < limit // 100
    doc, message, peak = load_or_refuse(path, limit)
    assert doc is None and peak < limit + 16 * 2**20  # at most the limit's bytes were unpacked
    assert message == f"{path}: its JSON is over the {limit} bytes a replay JSON may have, unpacked"


def test_a_gzipped_replay_loads_as_the_plain_one_and_a_cut_gzip_is_refused(replay):
    path, real, folder = replay.path, replay.bytes, replay.folder
    packed = gzip.compress(real)
    assert fr.load_episodes(write_case(folder, packed, "episode.json.gz")) == json.loads(real)
    cut = write_case(folder, packed[: len(packed) // 2], "cut.json.gz")
    with pytest.raises(fr.ReplayFileError, match=f"{cut}: its gzip stream is cut short"):
        fr.load_episodes(cut)
    tail = write_case(folder, packed + b"junk", "tail.json.gz")
    with pytest.raises(fr.ReplayFileError, match=f"{tail}: 4 bytes follow its gzip stream"):
        fr.load_episodes(tail)


def test_a_folder_a_fifo_a_device_and_a_missing_file_are_refused_without_blocking(replay, tmp_path):
    fifo = tmp_path / "episode.fifo"
    os.mkfifo(fifo)
    link = tmp_path / "link.json"
    link.symlink_to(fifo)
    cases = {tmp_path: "a folder, not a replay JSON file",
             fifo: "not a regular file (a FIFO, socket or device is never read)",
             link: "not a regular file (a FIFO, socket or device is never read)",
             "/dev/zero": "not a regular file (a FIFO, socket or device is never read)",
             tmp_path / "missing.json": "no such file"}
    for path, why in cases.items():
        with time_bound(CASE_S):  # a blocking open of the FIFO would end here, failing the test
            with pytest.raises(fr.ReplayFileError) as refused:
                fr.load_episodes(path)
        assert str(refused.value) == f"{path}: {why}"
    run = subprocess.run([sys.executable, "-m", "fairgrasp.rerun", str(fifo), "--rrd",
                          str(tmp_path / "x.rrd")], capture_output=True, text=True, timeout=60)
    assert run.returncode == 2 and f"{fifo}: not a regular file" in run.stderr, run.stderr
    assert not (tmp_path / "x.rrd").exists()


def test_a_refused_field_is_named_with_its_value(replay, tmp_path):
    path, real = replay.path, replay.bytes
    cases = [
        (["methods", 0, "trajectory", "rows", 3, "tcp_xyz"], [0.1, "a", 0.2],
         "methods[0].trajectory.rows[3].tcp_xyz[1]: 'a': expected a finite number [m]"),
        (["methods", 1, "trajectory", "rows", 0, "time_s"], -1.0,
         "methods[1].trajectory.rows[0].time_s: -1.0: expected a finite number in [0, 1e+09] [s]"),
        (["methods", 0, "contact_forces"], [],
         "methods[0].contact_forces: 0 entries for 54 rows: expected one per row"),
        (["methods", 1, "method"], "Scripted  Baseline",
         "methods[1].method: 'Scripted  Baseline' has the entity name `scripted_baseline` of "
         "methods[0]: give the methods distinct names"),
        (["fairgrasp_replay_json"], 2, "fairgrasp_replay_json = 2: this reader knows format 1"),
    ]
    for keys, value, message in cases:
        doc = json.loads(real)
        node = doc
        for key in keys[:-1]:
            node = node[key]
        node[keys[-1]] = value
        case = tmp_path / "case.json"
        case.write_text(json.dumps(doc), encoding="utf-8")
        with pytest.raises(fr.ReplayFileError) as refused:
            fr.load_episodes(case)
        assert str(refused.value).startswith(f"{case}: {message}"), str(refused.value)
    # NaN reaches the checks through a dict given to save; a file with NaN is not JSON.
    doc = json.loads(real)
    doc["methods"][0]["trajectory"]["rows"][5]["reward"] = float("nan")
    with pytest.raises(fr.ReplayFileError,
                       match=r"the episodes given: methods\[0\].trajectory.rows\[5\].reward: nan"):
        fr.save(doc, tmp_path / "x.rrd")
    assert not (tmp_path / "x.rrd").exists()


def test_a_replay_with_a_damaged_urdf_is_written_or_refused_naming_the_file(replay, tmp_path):
    path, real = replay.path, replay.bytes
    urdf = json.loads(real)["urdf"]
    damaged = [urdf[: len(urdf) * k // 8] for k in range(1, 8)] + [
        "garbage", "<robot name='x'/>", urdf.replace('type="prismatic"', 'type="sliding"'),
        urdf.replace("<axis xyz=\"1.0 0 0\"/>", ""), urdf.replace('name="palm"', 'name="hand"')]
    outcomes = []
    for k, text in enumerate(damaged):
        doc = json.loads(real)
        doc["urdf"] = text
        case = tmp_path / f"urdf{k}.json"
        case.write_text(json.dumps(doc), encoding="utf-8")
        try:
            fr.save(case, tmp_path / f"urdf{k}.rrd")
            outcomes.append("written")
        except fr.ReplayFileError as e:
            assert str(e).startswith(f"{case}: urdf: Rerun's URDF loader refuses it: "), str(e)
            assert not (tmp_path / f"urdf{k}.rrd").exists()
            outcomes.append("refused")
    assert "refused" in outcomes, outcomes  # a cut URDF is not XML
