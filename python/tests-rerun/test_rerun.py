"""fairgrasp.rerun: a `fairgrasp replay --json` episode (two methods on one scenario) written as a
Rerun .rrd, read back with Rerun's own reader (rerun.chunk.RrdReader), and checked: the entity
paths of each method, and the first and last step and simulated second equal the episode's.

Needs the venv of scripts/requirements-rerun.txt and FAIRGRASP_BIN (the fairgrasp binary; set by
tests/rerun_file.rs)."""

import json
import os
import subprocess
import sys

import pyarrow.compute as pc
import pytest
import rerun.chunk

import fairgrasp.rerun as fr


@pytest.fixture(scope="module")
def episode(tmp_path_factory):
    """`fairgrasp replay --json` of open_loop and oracle on the sector preset's scenario 0."""
    out = tmp_path_factory.mktemp("replay") / "episode.json"
    binary = os.environ["FAIRGRASP_BIN"]
    subprocess.run([binary, "replay", "--policy", "open_loop", "--policy", "oracle",
                    "--json", str(out)], check=True, capture_output=True)
    with open(out, encoding="utf-8") as f:
        return out, json.load(f)


def read_back(rrd):
    """Each entity path of the recording → (component names, (min, max) of `step`, max of
    `sim_time` [s]), through Rerun's reader."""
    store = rerun.chunk.RrdReader(rrd).stream().collect()
    out = {}
    for chunk in store.stream():
        batch = chunk.to_record_batch()
        names, steps, seconds = out.setdefault(chunk.entity_path, (set(), [], []))
        names.update(n for n in batch.schema.names if ":" in n)
        if "step" in batch.schema.names:
            steps += [pc.min(batch["step"]).as_py(), pc.max(batch["step"]).as_py()]
        if "sim_time" in batch.schema.names:
            nanos = pc.max(batch["sim_time"].cast("int64")).as_py()
            seconds.append(nanos * 1e-9)
    return out


def test_two_methods_make_one_subtree_each_over_the_episodes_steps(episode, tmp_path):
    path, doc = episode
    rrd = tmp_path / "episode.rrd"
    summary = fr.save(path, rrd)
    entities = read_back(rrd)
    assert [m["method"] for m in doc["methods"]] == ["scripted baseline", "oracle script"]
    for m in doc["methods"]:
        name = fr.entity_name(m["method"])
        rows = m["trajectory"]["rows"]
        # Robot links from the URDF loader, joints animated, scene, path and time series.
        for suffix in ("fairino_fr3/collision_geometries/capsule/shoulder_link/collision_0",
                       "fairino_fr3/collision_geometries/box/finger_left_pad/collision_0",
                       "joints/j1", "joints/j6", "joints/finger_left_joint", "table", "cube",
                       "tcp_path", "reward", "return", "phase", "pad_contact/left",
                       "contact_force/pad_left", "contact_force/robot_strongest",
                       "wrist_force/z"):
            assert f"/{name}/{suffix}" in entities, (name, suffix, sorted(entities)[:20])
        shoulder = f"/{name}/fairino_fr3/collision_geometries/capsule/shoulder_link/collision_0"
        assert "Capsules3D:radii" in entities[shoulder][0]
        assert "Transform3D:quaternion" in entities[f"/{name}/joints/j1"][0]
        names, steps, seconds = entities[f"/{name}/reward"]
        assert (min(steps), max(steps)) == (rows[0]["step"], rows[-1]["step"]) == (0, len(rows) - 1)
        # sim_time is stored in whole nanoseconds.
        assert max(seconds) == pytest.approx(rows[-1]["time_s"], abs=1e-9)
        _, cube_steps, _ = entities[f"/{name}/cube"]
        assert (min(cube_steps), max(cube_steps)) == (0, len(rows) - 1)
        # The pads squeeze the cube at the end of a successful lift.
        assert m["outcome"] == "success"
        assert min(m["contact_forces"][-1]["pad_cube_n"]) > 1.0
    assert [s[0] for s in summary["methods"]] == ["scripted_baseline", "oracle_script"]
    assert summary["methods"][0][1:3] == (0, len(doc["methods"][0]["trajectory"]["rows"]) - 1)


def test_the_cli_writes_the_file_and_a_bare_trajectory_is_one_method(episode, tmp_path):
    path, doc = episode
    bare = tmp_path / "trajectory.json"
    bare.write_text(json.dumps(doc["methods"][1]["trajectory"]), encoding="utf-8")
    rrd = tmp_path / "bare.rrd"
    run = subprocess.run([sys.executable, "-m", "fairgrasp.rerun", str(bare), "--rrd", str(rrd),
                          "--urdf", str(_urdf(tmp_path, doc))], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    entities = read_back(rrd)
    assert "/episode/joints/j3" in entities
    assert not any(e.startswith("/episode/contact_force") for e in entities)
    assert not any(e.startswith("/oracle_script") for e in entities)


def test_bad_input_is_refused_with_the_file_named(tmp_path):
    bad = tmp_path / "not_a_replay.json"
    bad.write_text('{"hello": 1}', encoding="utf-8")
    with pytest.raises(fr.ReplayFileError, match="not_a_replay.json: neither"):
        fr.save(bad, tmp_path / "x.rrd")
    empty = tmp_path / "empty.json"
    empty.write_text('{"fairgrasp_replay_json": 1, "methods": []}', encoding="utf-8")
    with pytest.raises(fr.ReplayFileError,
                       match="empty.json: methods: expected a list of 1–32 entries, got 0 entries"):
        fr.save(empty, tmp_path / "x.rrd")
    with pytest.raises(fr.ReplayFileError, match=r"the episodes given: methods\[0\].method: missing"):
        fr.save({"methods": [{"trajectory": {"rows": [{}]}}]}, tmp_path / "x.rrd")
    with pytest.raises(ValueError, match="spacing_m = nan"):
        fr.save(empty, tmp_path / "x.rrd", spacing_m=float("nan"))
    assert not (tmp_path / "x.rrd").exists()
    run = subprocess.run([sys.executable, "-m", "fairgrasp.rerun", str(bad), "--rrd",
                          str(tmp_path / "x.rrd")], capture_output=True, text=True)
    assert run.returncode == 2 and "not_a_replay.json" in run.stderr


def test_without_rerun_the_package_imports_and_save_names_the_requirements(tmp_path):
    # A fresh interpreter in which `import rerun` fails, as in the main suite's venv.
    code = (
        "import sys; sys.modules['rerun'] = None\n"
        "import fairgrasp, fairgrasp.rerun as fr\n"
        "try:\n"
        "    fr.save({'methods': []}, sys.argv[1])\n"
        "except ImportError as e:\n"
        "    print('ImportError:', e)\n"
    )
    run = subprocess.run([sys.executable, "-c", code, str(tmp_path / "x.rrd")],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "ImportError:" in run.stdout and "scripts/requirements-rerun.txt" in run.stdout
    assert not (tmp_path / "x.rrd").exists()


def _urdf(tmp_path, doc):
    path = tmp_path / "fr3.urdf"
    path.write_text(doc["urdf"], encoding="utf-8")
    return path
