"""fairgrasp.tune: a sweep of Rust trainings as Ray Tune trials under ASHA, on a local Ray with 2
CPUs (run by tests/ray_tune.rs through scripts/python-package-test.sh in target/python-ray-venv,
with the train-enabled binary in FAIRGRASP_BIN). One tiny sweep, 2 seeds × 2 learning rates on
`nudged` (20 updates of 1 024 steps, an evaluation of 20 held-out scenarios every 2 updates, one
thread per trial), then facts about what it left: run folders, reasons, the best config."""

import csv
import json
import os
import subprocess
import sys
import time

import pytest

try:
    import tomllib  # Python 3.11+
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

import fairgrasp.tune as ft

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
UPDATES, EVAL_EVERY = 20, 2
SEEDS, RATES = [0, 1], [3e-4, 3e-2]


@pytest.fixture(scope="module")
def binary():
    path = os.environ.get("FAIRGRASP_BIN")
    if not path:
        pytest.skip("FAIRGRASP_BIN not set (run through cargo test --test ray_tune)")
    return path


@pytest.fixture(scope="module")
def sweep(binary, tmp_path_factory):
    import ray

    out = tmp_path_factory.mktemp("sweep") / "lr"
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        start = time.time()
        table = ft.sweep("residual_miscalibrated", out, seeds=SEEDS, grid={"ppo.learning_rate": RATES},
                         fixed={"preset": "nudged", "total_timesteps": UPDATES * 1024, "eval_every": EVAL_EVERY,
                                "eval_episodes": 20, "threads": 1},
                         binary=binary, grace_period=1, reduction_factor=2)
        wall = time.time() - start
    finally:
        ray.shutdown()
    # What the sweep took and found (pytest -s shows it; docs/python.md quotes a run).
    print(f"\nsweep: {wall:.1f} s in sweep(), Tune's fit {table['wall_s']:.1f} s on {table['ray_cpus']} CPUs")
    print(ft.format_table(table))
    return table


def eval_column(run_dir):
    with open(os.path.join(run_dir, "metrics.csv")) as f:
        rows = list(csv.DictReader(f))
    return rows, [float(r["eval_success_rate"]) for r in rows if r["eval_success_rate"]]


def test_every_trial_keeps_its_run_folder_with_metrics_and_tensorboard_events(sweep):
    assert len(sweep["trials"]) == len(SEEDS) * len(RATES)
    assert {(t["seed"], t["set"]["ppo.learning_rate"]) for t in sweep["trials"]} == {
        (s, r) for s in SEEDS for r in RATES}
    for t in sweep["trials"]:
        rows, _ = eval_column(t["run_dir"])
        assert rows, f"{t['trial']}: metrics.csv has no rows"
        events = [f for f in os.listdir(t["run_dir"]) if f.startswith("events.out.tfevents")]
        assert events and events == t["event_files"], t["trial"]
        assert os.path.getsize(os.path.join(t["run_dir"], events[0])) > 0
        # The config the trial trained is the recipe with its seed and learning rate.
        with open(os.path.join(t["run_dir"], "config.toml"), "rb") as f:
            trained = tomllib.load(f)
        assert trained["seed"] == t["seed"] and trained["preset"] == "nudged"
        assert trained["ppo"]["learning_rate"] == t["set"]["ppo.learning_rate"]


def test_what_tune_got_is_the_evaluation_column_of_metrics_csv(sweep):
    for t in sweep["trials"]:
        _, column = eval_column(t["run_dir"])
        assert t["evaluations"] >= 1, t["trial"]
        assert t["reported"] == column[: t["evaluations"]], t["trial"]


def test_each_trial_completed_or_was_stopped_by_asha_with_its_reason(sweep):
    out = sweep["out"]
    with open(os.path.join(out, "asha_stops.jsonl")) as f:
        stops = {d["trial"]: d for d in map(json.loads, f)}
    for t in sweep["trials"]:
        assert not t["left_running"], f"{t['trial']}: its training outlived the trial"
        if t["status"] == "completed":
            assert t["trial"] not in stops
            assert t["evaluations"] == UPDATES // EVAL_EVERY
            # eval.json is the run's last evaluation: the last one Tune got.
            assert t["final"]["episodes"] == 20 and t["final"]["success_rate"] == t["last_success"]
            rows, _ = eval_column(t["run_dir"])
            assert len(rows) == UPDATES
            assert t["reason"] == f"trained its {UPDATES // EVAL_EVERY} evaluations to the end"
        else:
            assert t["status"] == "stopped by ASHA", (t["trial"], t["status"], t["reason"])
            stop = stops[t["trial"]]
            assert stop["evaluations"] == t["evaluations"] < UPDATES // EVAL_EVERY
            assert stop["eval_success"] == t["last_success"] < stop["rung"]["cutoff"]
            # Its training was ended by SIGTERM before it finished: by the trial, which records
            # the exit status, or (when Ray ends the trial's process first) by the kernel's
            # death signal, unrecorded; either way it is not left running (asserted above).
            assert ("its training was ended (exit status -15)" in t["reason"]
                    or t["reason"].endswith(ft.ENDED_WITH_ITS_TRIAL)), t["reason"]
            assert t["final"] is None
            rows, _ = eval_column(t["run_dir"])
            assert len(rows) < UPDATES
    print("stopped by ASHA:", [t["trial"] for t in sweep["trials"] if t["status"] != "completed"])


def test_the_best_config_is_the_trial_with_the_highest_reported_success(sweep):
    highest = max(v for t in sweep["trials"] for v in t["reported"])
    best = sweep["best"]
    assert best["best_success"] == highest
    trial = next(t for t in sweep["trials"] if t["trial"] == best["trial"])
    assert max(trial["reported"]) == highest and trial["set"] == best["set"] and trial["seed"] == best["seed"]
    # Tune's own answer (its best over every reported result) is a trial that reached it too.
    tune_best = next(t for t in sweep["trials"] if t["trial"] == best["tune_best_trial"])
    assert max(tune_best["reported"]) == highest


def test_the_table_is_written_as_returned(sweep):
    with open(os.path.join(sweep["out"], "sweep.json")) as f:
        assert json.load(f) == json.loads(json.dumps(sweep))
    with open(os.path.join(sweep["out"], "sweep.md")) as f:
        md = f.read()
    assert all(t["trial"] in md for t in sweep["trials"]) and f"Best: {sweep['best']['trial']}" in md


@pytest.mark.parametrize("name", sorted(f[:-5] for f in os.listdir(os.path.join(ROOT, "assets", "experiments"))
                                        if f.endswith(".toml")))
def test_the_toml_a_trial_trains_reads_back_as_the_recipe(name):
    with open(os.path.join(ROOT, "assets", "experiments", name + ".toml"), "rb") as f:
        recipe = tomllib.load(f)
    assert tomllib.loads(ft.to_toml(recipe)) == recipe


def cli(*args, env=None):
    return subprocess.run([sys.executable, "-m", "fairgrasp.tune", *args], capture_output=True, text=True,
                          timeout=120, env=env, cwd=ROOT)


@pytest.mark.parametrize("args, message", [
    (["--grid", "ppo.learnin_rate=1e-3,3e-3"], "unknown field `learnin_rate`"),
    # The binary's words (`-1` or `-1.0`, with or without SB3's default after the bounds).
    (["--grid", "ppo.learning_rate=-1,3e-3"], ("learning_rate = -1", "must be in (0, 1]")),
    (["--set", "preset=nowhere"], "nowhere: no such preset"),
    (["--seeds", "1", "1"], "seeds [1, 1]: a seed is given twice"),
    (["--set", "ppo.learning_rate"], "expected key=value"),
    (["--grid", "ppo.learning_rate=1e-3,1e-3"], "a value is given twice"),
])
def test_bad_input_is_refused_before_anything_runs(binary, tmp_path, args, message):
    out = tmp_path / "sweep"
    proc = cli("residual_miscalibrated", "--out", str(out), "--bin", binary, *args)
    assert proc.returncode == 2, proc.stderr
    messages = message if isinstance(message, tuple) else (message,)
    assert all(m in proc.stderr for m in messages) and proc.stderr.startswith("error: "), proc.stderr
    assert not out.exists()


def test_an_out_folder_with_files_is_refused_and_a_missing_binary_named(binary, tmp_path):
    (tmp_path / "keep.txt").write_text("a file")
    proc = cli("residual_miscalibrated", "--out", str(tmp_path), "--bin", binary)
    assert proc.returncode == 2 and "holds files" in proc.stderr, proc.stderr
    proc = cli("residual_miscalibrated", "--out", str(tmp_path / "new"), "--bin", str(tmp_path / "nope"))
    assert proc.returncode == 2 and f"{tmp_path / 'nope'}: not an executable file" in proc.stderr, proc.stderr
    assert (tmp_path / "keep.txt").read_text() == "a file"
