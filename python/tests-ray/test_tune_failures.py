"""fairgrasp.tune when things go wrong (issue 60, item 6): a trial whose training fails is reported
with the trainer's own message, a trial whose trainer is killed with the signal; a sweep whose
driver is killed and then resumed keeps its finished trials untouched and continues the others
from their checkpoints; a resumed sweep with other arguments, and bad arguments, are refused
before Ray starts.

The trainings are tiny (the `fixed` preset, 2 envs, updates of 32 steps, 1 thread): the whole
file takes about 1–2 minutes on 2 cores. Needs FAIRGRASP_BIN (set by tests/ray_tune.rs)."""

import json
import os
import signal
import subprocess
import sys
import threading
import time

import pytest

import fairgrasp.tune as ft

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
#: A pure-agent recipe that trains in seconds (20 updates of 32 steps, an evaluation of 2
#: episodes every 2 updates).
TINY = """preset = "fixed"
total_timesteps = 640
n_envs = 2
threads = 1
eval_every = 2
eval_episodes = 2
[ppo]
n_steps = 16
batch_size = 16
n_epochs = 1
learning_rate = 0.0003
"""
#: Overrides that make it diverge at update 5 with `ppo.learning_rate = 1.0`: the entropy bonus
#: dominates the loss and σ overflows (rl/tests/errors.rs), so the trainer stops with an error
#: naming the update.
DIVERGING = {"ppo.n_epochs": 10, "ppo.ent_coef": 100.0, "model.log_std_init": 2.0}


@pytest.fixture(scope="module")
def binary():
    path = os.environ.get("FAIRGRASP_BIN")
    if not path:
        pytest.skip("FAIRGRASP_BIN not set (run through cargo test --test ray_tune)")
    return path


@pytest.fixture(scope="module")
def recipe(tmp_path_factory):
    path = tmp_path_factory.mktemp("recipe") / "tiny.toml"
    path.write_text(TINY)
    return str(path)


def evaluation_rows(run_dir):
    rows, _, _ = ft.read_evaluations(os.path.join(run_dir, "metrics.csv"))
    return rows


def pid_of(folder):
    with open(os.path.join(folder, "pid")) as f:
        return int(f.read())


def wait_for(condition, timeout_s, what):
    deadline = time.time() + timeout_s
    while time.time() < deadline:
        if condition():
            return
        time.sleep(0.2)
    raise AssertionError(f"waited {timeout_s} s for {what}")


def alive(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.fixture(scope="module")
def failing_sweep(binary, recipe, tmp_path_factory):
    """Two trials of TINY with DIVERGING: learning rate 1.0 (its training diverges at update 5) and
    3e-4 over 40 000 steps,
    whose trainer this test kills with SIGKILL after its first evaluation. ASHA's grace period is
    longer than either lives, so neither is stopped by ASHA."""
    import ray

    out = tmp_path_factory.mktemp("failing") / "sweep"
    folder = os.path.join(out, "trials", ft.trial_name(0, {"ppo.learning_rate": 3e-4}))
    killed = {}

    def kill_after_first_evaluation():
        wait_for(lambda: os.path.exists(os.path.join(folder, "pid"))
                 and evaluation_rows(os.path.join(folder, "run")), 120, "the 3e-4 trial's first evaluation")
        killed["pid"] = pid_of(folder)
        os.kill(killed["pid"], signal.SIGKILL)

    killer = threading.Thread(target=kill_after_first_evaluation, daemon=True)
    killer.start()
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        table = ft.sweep(recipe, out, grid={"ppo.learning_rate": [1.0, 3e-4]},
                         fixed={**DIVERGING, "total_timesteps": 40_000}, binary=binary, grace_period=600)
    finally:
        ray.shutdown()
    killer.join(timeout=5)
    print(ft.format_table(table))
    return table, killed


def test_a_trial_whose_training_diverges_is_failed_with_the_trainers_message(failing_sweep):
    table, _ = failing_sweep
    trial = next(t for t in table["trials"] if t["set"] == {"ppo.learning_rate": 1.0})
    assert trial["status"] == "failed"
    # The trainer's own error line, not a bare failure or a traceback.
    assert trial["reason"].startswith("fairgrasp train failed (exit status 1) after 2 evaluations: update 5 failed: "), \
        trial["reason"]
    assert "the policy diverged" in trial["reason"] and "Traceback" not in trial["reason"]
    with open(os.path.join(table["out"], "sweep.md")) as f:
        assert f"- {trial['trial']}: failed: {trial['reason']}" in f.read()
    # What Tune got before the failure is the run's evaluation column (updates 2 and 4).
    assert trial["reported"] == [r[ft.METRIC] for r in evaluation_rows(trial["run_dir"])]
    assert len(trial["reported"]) == 2 and trial["final"] is None


def test_a_trial_whose_trainer_is_killed_is_failed_with_the_signal(failing_sweep):
    table, killed = failing_sweep
    trial = next(t for t in table["trials"] if t["set"] == {"ppo.learning_rate": 3e-4})
    assert "pid" in killed, "the test's killer thread never found the trainer"
    assert trial["status"] == "failed" and not trial["left_running"]
    assert trial["reason"].startswith(f"fairgrasp train was killed by SIGKILL (signal 9) after "
                                      f"{trial['evaluations']} evaluations"), trial["reason"]
    assert trial["evaluations"] >= 1 and not alive(killed["pid"])
    with open(os.path.join(table["out"], "trials", trial["trial"], "trial.json")) as f:
        assert json.load(f)["exit"] == -9


def cli(*args, **kwargs):
    return subprocess.run([sys.executable, "-m", "fairgrasp.tune", *args], capture_output=True, text=True,
                          timeout=300, cwd=ROOT, **kwargs)


def snapshot(folder):
    """Every file under ``folder``: its bytes and modification time."""
    out = {}
    for where, _, files in os.walk(folder):
        for name in files:
            path = os.path.join(where, name)
            with open(path, "rb") as f:
                out[os.path.relpath(path, folder)] = (f.read(), os.stat(path).st_mtime_ns)
    return out


def test_a_killed_sweep_resumed_keeps_its_finished_trial_and_continues_the_other(binary, recipe, tmp_path):
    out = tmp_path / "sweep"
    args = [recipe, "--out", str(out), "--bin", binary, "--grid", "total_timesteps=640,20000",
            "--set", "eval_every=20", "--cpus", "2", "--cpus-per-trial", "1", "--grace-period", "30"]
    short = out / "trials" / ft.trial_name(0, {"total_timesteps": 640})
    long = out / "trials" / ft.trial_name(0, {"total_timesteps": 20000})
    driver = subprocess.Popen([sys.executable, "-m", "fairgrasp.tune", *args], cwd=ROOT, start_new_session=True,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_for(lambda: (ft._read_json(str(short / "trial.json")) or {}).get("status") == "completed"
                 and evaluation_rows(str(long / "run")), 180, "the short trial's end and the long one's evaluation")
        driver.kill()  # SIGKILL: no handler runs, as when a machine or a session dies
        driver.wait()
        trainer = pid_of(str(long))
        wait_for(lambda: not alive(trainer), 60, "the long trial's training to end with the sweep")
    finally:
        if driver.poll() is None:
            driver.kill()
        with __import__("contextlib").suppress(ProcessLookupError):
            os.killpg(driver.pid, signal.SIGKILL)  # what Ray left in the driver's session, if anything
    assert not (out / "sweep.json").exists()
    kept = snapshot(short)
    checkpoint = ft._read_json(str(long / "run" / "checkpoints" / "latest" / "meta.json"))
    with open(long / "run" / "metrics.csv") as f:
        before = f.read().splitlines()[: 1 + checkpoint["updates"]]

    # Another request in the same folder is refused by name, before Ray starts.
    other = cli(*[a if a != "total_timesteps=640,20000" else "total_timesteps=640,30000" for a in args], "--resume")
    assert other.returncode == 2, other.stderr
    assert "is not resumed: grid.total_timesteps: [640, 20000] → [640, 30000]" in other.stderr, other.stderr
    assert not (out / "tune-resume-1").exists()

    resumed = cli(*args, "--resume")
    assert resumed.returncode == 0, resumed.stderr
    with open(out / "sweep.json") as f:
        table = json.load(f)
    rows = {t["trial"]: t for t in table["trials"]}
    assert table["kept"] == 1 and len(rows) == 2
    first = rows[short.name]
    assert first["kept"] and first["status"] == "completed" and first["evaluations"] == 1
    assert snapshot(short) == kept  # not trained again: every file as the killed sweep left it
    second = rows[long.name]
    assert not second["kept"] and second["status"] == "completed", second
    # 625 updates: an evaluation every 20 and one after the last.
    assert second["evaluations"] == 32 and second["final"] is not None
    with open(long / "run" / "metrics.csv") as f:
        after = f.read().splitlines()
    assert len(after) == 1 + -(-20000 // 32) and after[: len(before)] == before  # continued, not restarted
    with open(long / "train.log") as f:
        attempts = [line for line in f if line.startswith("--- ")]
    assert len(attempts) == 2 and attempts[1].rstrip().endswith("--resume") and "--resume" not in attempts[0]
    assert (out / "tune").is_dir() and (out / "tune-resume-1").is_dir()
    assert f"- {short.name}: completed (kept from an earlier run of the sweep): " in resumed.stdout


@pytest.mark.parametrize("args, message", [
    (["--seeds", *map(str, range(1025))], "1025 seeds × 1 combinations = 1025 trials: at most 1024"),
    (["--cpus", "0"], "num_cpus 0: the local Ray instance's CPUs, an integer in 1–4096"),
    (["--cpus", "2", "--cpus-per-trial", "3"], "cpus_per_trial 3: more than the 2 CPUs of the local Ray instance"),
    (["--grid", "ppo.n_steps=16,abc"], "trial seed0_ppo.n_steps=abc: the binary refuses its config"),
    (["--grid", "ppo..n_steps=16"], "expected key=value"),
    (["--resume"], "no sweep to resume"),
    (["--resume", "--force"], "force and resume: choose one"),
    (["--grace-period", "99"], "grace_period 99: more than the 10 evaluations a trial makes"),
])
def test_bad_sweep_arguments_are_refused_before_ray_starts(binary, recipe, tmp_path, args, message):
    out = tmp_path / "sweep"
    proc = cli(recipe, "--out", str(out), "--bin", binary, *args)
    assert proc.returncode == 2 and proc.stderr.startswith("error: ") and message in proc.stderr, proc.stderr
    assert not out.exists() and "ray" not in proc.stderr.lower().replace("ray instance", "")


def test_an_unknown_or_unreadable_recipe_and_bad_api_arguments_are_refused_by_name(binary, recipe, tmp_path):
    proc = cli("no_such_recipe", "--out", str(tmp_path / "a"), "--bin", binary)
    assert proc.returncode == 2 and "recipe no_such_recipe: not a shipped recipe (" in proc.stderr, proc.stderr
    not_toml = tmp_path / "notes.toml"
    not_toml.write_bytes(b"preset = \n\xff")
    cases = [
        (dict(recipe=str(not_toml)), f"recipe {not_toml}: not a TOML file"),
        (dict(recipe=str(tmp_path)), f"recipe {tmp_path}: not a regular file"),
        (dict(recipe=recipe, seeds=5), "seeds 5: give a list of integers"),
        (dict(recipe=recipe, seeds=[True]), "seeds [True]: give one or more integers"),
        (dict(recipe=recipe, grid=[1e-3]), "grid [0.001]: give a dict of dotted recipe keys"),
        (dict(recipe=recipe, grid={"ppo.learning_rate": 1e-3}), "grid ppo.learning_rate: give a non-empty list"),
        (dict(recipe=recipe, grid={"ppo.learning_rate": [1e-3, 1e-3]}), "a value is given twice"),
        (dict(recipe=recipe, fixed={"ppo learning_rate": 1}), "fixed 'ppo learning_rate': not a dotted recipe key"),
        (dict(recipe=recipe, verbose=3), "verbose 3: must be 0, 1 or 2"),
    ]
    for kwargs, message in cases:
        out = tmp_path / "b"
        with pytest.raises(ft.SweepError) as refused:
            ft.sweep(out=out, binary=binary, **kwargs)
        assert message in str(refused.value), (kwargs, str(refused.value))
        assert not out.exists()
