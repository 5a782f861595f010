"""fairgrasp.train runs the Rust trainer: the run folder `fairgrasp train` writes (the same
network's weights, bit for bit, and the same evaluation as the CLI on the same config), progress after
every update, misspelt overrides refused with the valid keys."""

import importlib
import json
import os
import shutil
import subprocess
import tempfile

import pytest

import fairgrasp

TINY = dict(preset="sector", total_timesteps=1024, n_envs=2, threads=1, eval_every=2, eval_episodes=4, seed=3)


@pytest.fixture
def tmp(request):
    path = tempfile.mkdtemp(prefix=f"fairgrasp-{request.node.name}-{os.getpid()}-")
    yield path
    shutil.rmtree(path, ignore_errors=True)


def test_train_writes_the_run_folder_the_cli_writes(tmp, cli):
    seen = []
    run = os.path.join(tmp, "python")
    report = fairgrasp.train("residual_miscalibrated", run, progress=seen.append, **TINY)
    # 128 steps × 2 envs per update: 4 updates, progress after each.
    assert [p["timesteps"] for p in seen] == [256, 512, 768, 1024]
    assert all(p["total"] == 1024 for p in seen)
    assert [p["eval"] is not None for p in seen] == [False, True, False, True]
    for name in ("config.toml", "metrics.csv", "eval.json", "checkpoints/latest/model.bpk"):
        assert os.path.exists(os.path.join(run, name)), name
    with open(os.path.join(run, "metrics.csv")) as f:
        assert len(f.read().strip().splitlines()) == 1 + 4
    with open(os.path.join(run, "eval.json")) as f:
        written = json.load(f)
    assert report["success_rate"] == written["success_rate"] == seen[-1]["eval"]
    assert report["episodes"] == len(report["results"]) == 4
    # The CLI on the config the Python run saved: the same network and the same evaluation.
    other = os.path.join(tmp, "cli")
    path = os.environ["FAIRGRASP_BIN"]
    subprocess.run([path, "train", "--config", os.path.join(run, "config.toml"), "--run-dir", other],
                   check=True, capture_output=True)
    with open(os.path.join(run, "eval.json"), "rb") as a, open(os.path.join(other, "eval.json"), "rb") as b:
        assert a.read() == b.read()
    python_weights = burnpack_data(os.path.join(run, "checkpoints/latest/model.bpk"))
    cli_weights = burnpack_data(os.path.join(other, "checkpoints/latest/model.bpk"))
    assert len(python_weights) > 10_000
    assert python_weights == cli_weights


def burnpack_data(path):
    """The tensor bytes of a burnpack file (model.bpk): after the 10-byte header (magic, version,
    metadata length as a little-endian u32) and the CBOR metadata. The metadata holds burn's
    parameter ids, drawn anew in every process, so only the weights can be compared."""
    with open(path, "rb") as f:
        raw = f.read()
    assert raw[:4] == b"NRUB", path
    meta_len = int.from_bytes(raw[6:10], "little")
    return raw[10 + meta_len:]


def test_train_refuses_a_misspelt_override(tmp):
    with pytest.raises(ValueError, match="unknown field `total_timestep`.*total_timesteps"):
        fairgrasp.train("residual_miscalibrated", os.path.join(tmp, "r"), total_timestep=10)
    with pytest.raises(ValueError, match="n_envs = 0"):
        fairgrasp.train("residual_miscalibrated", os.path.join(tmp, "r"), n_envs=0)
    assert not os.path.exists(os.path.join(tmp, "r", "metrics.csv"))


def test_a_resume_from_another_folder_trains_on_the_runs_copy_of_its_preset(tmp, monkeypatch):
    started, elsewhere = os.path.join(tmp, "a"), os.path.join(tmp, "b")
    os.makedirs(started)
    os.makedirs(elsewhere)
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    shutil.copy(os.path.join(root, "assets", "configs", "sector.toml"), os.path.join(started, "cell.toml"))
    run = os.path.join(tmp, "run")
    tiny = dict(TINY, preset="cell.toml", total_timesteps=512)
    monkeypatch.chdir(started)
    fairgrasp.train("residual_miscalibrated", run, **tiny)
    # Another folder's cell.toml is not even valid TOML: the resume must not read it.
    with open(os.path.join(elsewhere, "cell.toml"), "w") as f:
        f.write("[scene\n")
    monkeypatch.chdir(elsewhere)
    fairgrasp.train("residual_miscalibrated", run, resume=True, **dict(tiny, total_timesteps=1024))
    with open(os.path.join(run, "metrics.csv")) as f:
        assert len(f.read().strip().splitlines()) == 1 + 4


def test_the_test_builds_extension_has_the_trainer():
    """`cargo test --workspace` builds the extension with the cargo feature `train` (a default of
    python/Cargo.toml; only maturin's builds leave it out): these tests train with it."""
    assert fairgrasp._native.HAS_TRAIN is True


def test_without_the_trainer_train_says_how_to_get_it(tmp):
    """An extension built without `train` (pip install ./python, the default wheel) refuses
    `fairgrasp.train` naming the install command that brings it, and writes nothing."""
    module = importlib.import_module("fairgrasp.train")

    class NoTrainer:
        HAS_TRAIN = False

    with pytest.raises(RuntimeError, match=r"has no Rust trainer.*pip install \./python "
                                           r"--config-settings=build-args=\"--features train\""):
        module.require_trainer(NoTrainer())
    run = os.path.join(tmp, "r")
    original = module._native
    module._native = NoTrainer()
    try:
        with pytest.raises(RuntimeError, match="scripts/build-wheel.sh --features train"):
            fairgrasp.train("residual_miscalibrated", run, **TINY)
    finally:
        module._native = original
    assert not os.path.exists(run)
