"""A sweep of Rust PPO trainings as Ray Tune trials: seeds × recipe overrides (a grid), ASHA
stopping the trials whose held-out evaluation success falls behind.

    import fairgrasp.tune
    table = fairgrasp.tune.sweep("residual_miscalibrated", "runs/sweep_lr", seeds=[0, 1],
                                 grid={"ppo.learning_rate": [3e-4, 1e-3]},
                                 fixed={"preset": "nudged", "total_timesteps": 100_000})
    table["best"], table["trials"], table["wall_s"]

    python -m fairgrasp.tune residual_miscalibrated --out runs/sweep_lr --seeds 0 1 \\
        --grid ppo.learning_rate=3e-4,1e-3 --set preset=nudged --set total_timesteps=100000

Each trial writes the recipe with its seed and overrides to ``<out>/trials/<trial>/config.toml``
and runs ``fairgrasp train --config ... --run-dir <out>/trials/<trial>/run`` (the binary built
with ``--features train``: ``binary=``, else ``$FAIRGRASP_BIN``, else ``fairgrasp`` on PATH) as a
child process. It follows the run's ``metrics.csv`` as it grows and reports every evaluation
(the ``eval_success_rate`` column: ``eval_episodes`` held-out scenarios every ``eval_every``
updates) to Tune as ``eval_success``. ASHA (``time_attr`` = evaluations reported) compares
trials at its rungs; a trial it stops has its training process terminated (SIGTERM, then SIGKILL
after 10 s; a child also gets SIGTERM if its trial's process dies), and its run folder stays as
the kill left it (the trainer keeps a run resumable at any point: ``fairgrasp train --resume``).
Every trial's run folder (``config.toml``, ``metrics.csv``, TensorBoard's
``events.out.tfevents.*``, ``checkpoints/`` with ``best``, ``eval.json``: its latest evaluation)
stays under ``<out>/trials/``, beside the trial's ``config.toml`` and ``train.log``; Tune's own
records are in ``<out>/tune/``. The table (``<out>/sweep.json`` and ``<out>/sweep.md``, written
atomically) has per trial its config, status (``completed``, ``stopped by ASHA``, ``failed``) and
the reason, the evaluations reported, the best and last reported success, the final evaluation of a
completed trial (its ``eval.json``), and its wall time; the best config is the trial with the
highest success any evaluation reported.

Every trial config is checked by the binary before Ray starts (a misspelt key or a bad value is
refused naming the trial, with the binary's message). Needs ``pip install "ray[tune]==2.60.0"``.
"""

import argparse
import ctypes
import itertools
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

try:
    import tomllib  # Python 3.11+
except ModuleNotFoundError:  # Python 3.10, the package's oldest: the same parser, from PyPI
    import tomli as tomllib

METRIC = "eval_success"
MAX_TRIALS = 1024
_EXPERIMENTS = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                            "assets", "experiments")


class SweepError(ValueError):
    """Bad sweep input: names the argument, the value and what is allowed."""


# ---------------------------------------------------------------------------------------------
# Configs: the recipe, dotted overrides, TOML out.


def recipe_path(recipe):
    """A shipped recipe's name (``assets/experiments/<name>.toml`` of this checkout, or of the
    current folder) or a training config's path."""
    recipe = os.fspath(recipe)
    if recipe.endswith(".toml") or os.sep in recipe:
        if not os.path.isfile(recipe):
            raise SweepError(f"recipe {recipe}: no such file")
        return os.path.abspath(recipe)
    for folder in (_EXPERIMENTS, os.path.join("assets", "experiments")):
        path = os.path.join(folder, recipe + ".toml")
        if os.path.isfile(path):
            return os.path.abspath(path)
    names = sorted(f[:-5] for f in os.listdir(_EXPERIMENTS) if f.endswith(".toml")) if os.path.isdir(_EXPERIMENTS) else []
    raise SweepError(f"recipe {recipe}: not a shipped recipe ({', '.join(names) or 'none found'}) "
                     "nor a .toml path")


def parse_value(text):
    """A value as TOML reads it (``3e-4``, ``true``, ``[64, 64]``, ``"nudged"``); a bare word that
    is not TOML is a string (``nudged``)."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        if re.fullmatch(r"[A-Za-z0-9_.\-/]+", text):
            return text
        raise SweepError(f"value {text!r}: neither a TOML value nor a bare word") from None


def parse_assignment(text, *, many=False):
    """``key=value`` (``many``: ``key=v1,v2,...``; a TOML array as one value needs ``key=[..]``
    with ``many`` off) → (dotted key, value or list of values)."""
    key, sep, value = text.partition("=")
    key = key.strip()
    if not sep or not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)*", key) or not value.strip():
        raise SweepError(f"{text!r}: expected key=value with a dotted key such as ppo.learning_rate=3e-4")
    if many:
        values = [parse_value(v.strip()) for v in _split_top(value)]
        if len(set(map(repr, values))) != len(values):
            raise SweepError(f"{text!r}: a value is given twice")
        return key, values
    return key, parse_value(value.strip())


def _split_top(text):
    """Splits at commas outside brackets and quotes (``[64,64],[128,128]`` is two values)."""
    parts, depth, quote, cur = [], 0, None, ""
    for ch in text:
        if quote:
            quote = None if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch in "[{":
            depth += 1
        elif ch in "]}":
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
            continue
        cur += ch
    parts.append(cur)
    return parts


def set_key(table, dotted, value):
    """Sets ``a.b.c`` in nested dicts (missing tables are made; a key that is a value, not a
    table, is refused)."""
    *path, last = dotted.split(".")
    for i, part in enumerate(path):
        table = table.setdefault(part, {})
        if not isinstance(table, dict):
            raise SweepError(f"override {dotted}: {'.'.join(path[:i + 1])} is a value, not a table")
    table[last] = value


def _toml_value(v, where):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)  # a TOML basic string: the same escapes
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x, where) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_toml_key(k)} = {_toml_value(x, where)}" for k, x in v.items()) + " }"
    raise SweepError(f"{where}: {v!r} cannot be written as TOML")


def _toml_key(k):
    return k if re.fullmatch(r"[A-Za-z0-9_-]+", k) else json.dumps(k)


def to_toml(table, prefix=""):
    """A TOML document of nested dicts (values first, then tables; arrays of tables inline)."""
    lines, subtables = [], []
    for k, v in table.items():
        if isinstance(v, dict):
            subtables.append((k, v))
        else:
            lines.append(f"{_toml_key(k)} = {_toml_value(v, prefix + k)}")
    for k, v in subtables:
        name = f"{prefix}{_toml_key(k)}"
        lines.append(f"\n[{name}]")
        lines.append(to_toml(v, name + ".").strip("\n"))
    return "\n".join(line for line in lines if line != "") + "\n"


def _write_atomic(path, text):
    folder = os.path.dirname(path) or "."
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=".tmp-", suffix=os.path.basename(path))
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def trial_config(base, seed, overrides):
    """The recipe with the trial's seed and overrides laid over it."""
    config = json.loads(json.dumps(base))  # a deep copy of plain data
    for key, value in overrides.items():
        set_key(config, key, value)
    config["seed"] = int(seed)
    return config


def trial_name(seed, overrides):
    """``seed0`` + ``_<key>=<value>`` per override, file-name safe."""
    parts = [f"seed{seed}"] + [f"{k}={json.dumps(v) if not isinstance(v, str) else v}" for k, v in overrides.items()]
    return re.sub(r"[^A-Za-z0-9_.=+-]", "-", "_".join(parts))


# ---------------------------------------------------------------------------------------------
# The binary.


def find_binary(binary=None):
    """``binary``, else ``$FAIRGRASP_BIN``, else ``fairgrasp`` on PATH: an executable file."""
    path = binary or os.environ.get("FAIRGRASP_BIN") or shutil.which("fairgrasp")
    if not path:
        raise SweepError("no fairgrasp binary: pass binary= (--bin) or set FAIRGRASP_BIN to one built with "
                         "`cargo build --release --features train`")
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        raise SweepError(f"fairgrasp binary {path}: not an executable file")
    return os.path.abspath(path)


def check_config(binary, config_path, name):
    """Lets the binary read and check the config without training: ``--resume`` into an empty
    folder is refused *after* the config passed (``holds no run``); anything else is the
    config's error."""
    with tempfile.TemporaryDirectory(prefix="fairgrasp-tune-check-") as scratch:
        proc = subprocess.run([binary, "train", "--config", config_path, "--run-dir",
                               os.path.join(scratch, "run"), "--resume"],
                              capture_output=True, text=True, timeout=60)
    if proc.returncode == 0 or "holds no run" not in proc.stderr:
        message = (proc.stderr or proc.stdout).strip().splitlines()
        raise SweepError(f"trial {name}: the binary refuses its config: {' '.join(message[-3:]) or proc.returncode}")


def _die_with_parent():
    """In the child, before exec: SIGTERM when the thread that started it dies (the trial's
    process stopped by Tune), so no training outlives its trial. Linux only; elsewhere a no-op."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


def terminate(proc, grace_s=10.0):
    """SIGTERM, then SIGKILL after ``grace_s``; returns the exit status."""
    if proc.poll() is None:
        proc.send_signal(signal.SIGTERM)
        try:
            proc.wait(timeout=grace_s)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
    return proc.returncode


def read_evaluations(metrics_csv, offset=0, header=None):
    """The evaluation rows of ``metrics.csv`` from byte ``offset`` on (complete lines only):
    ``([{"update", "timesteps", "wall_s", "eval_success"}, ...], new_offset, header)``."""
    rows = []
    try:
        with open(metrics_csv, "rb") as f:
            f.seek(offset)
            data = f.read()
    except FileNotFoundError:
        return rows, offset, header
    end = data.rfind(b"\n") + 1
    for line in data[:end].decode().splitlines():
        cells = line.split(",")
        if header is None:
            header = cells
            continue
        if len(cells) != len(header):
            continue
        row = dict(zip(header, cells))
        if row.get("eval_success_rate"):
            rows.append({"update": int(row["update"]), "timesteps": int(row["timesteps"]),
                         "wall_s": float(row["wall_time_s"]), METRIC: float(row["eval_success_rate"])})
    return rows, offset + end, header


def _stop_requested():
    """Whether Tune asked this trial's function to stop (its session's stop event; an internal
    of Ray 2.60, read defensively: without it, the child still dies with the trial's process)."""
    try:
        from ray.train._internal.session import get_session

        session = get_session()
        return bool(session is not None and session.stop_event.is_set())
    except Exception:  # noqa: BLE001 - any change in Ray's internals: fall back to the death signal
        return False


# ---------------------------------------------------------------------------------------------
# The trial (runs in a Ray worker).


def _trial(config, *, base, binary, trials_dir, poll_s):
    from ray import tune

    seed, overrides = config["seed"], dict(config.get("set", {}))
    name = trial_name(seed, overrides)
    folder = os.path.join(trials_dir, name)
    run_dir = os.path.join(folder, "run")
    os.makedirs(folder, exist_ok=True)
    config_path = os.path.join(folder, "config.toml")
    _write_atomic(config_path, to_toml(trial_config(base, seed, overrides)))
    start = time.time()
    with open(os.path.join(folder, "train.log"), "w") as log:
        proc = subprocess.Popen([binary, "train", "--config", config_path, "--run-dir", run_dir],
                                stdout=log, stderr=subprocess.STDOUT, preexec_fn=_die_with_parent)
    _write_atomic(os.path.join(folder, "pid"), f"{proc.pid}\n")
    offset, header, reported, status = 0, None, 0, None
    try:
        while True:
            exited = proc.poll() is not None
            rows, offset, header = read_evaluations(os.path.join(run_dir, "metrics.csv"), offset, header)
            for row in rows:
                reported += 1
                tune.report({**row, "evaluations": reported, "trial": name})
            if exited:
                break
            if _stop_requested():
                status = "stopped"
                return
            time.sleep(poll_s)
        wall = time.time() - start
        if proc.returncode != 0:
            with open(os.path.join(folder, "train.log")) as f:
                tail = f.read().strip().splitlines()[-5:]
            status = "failed"
            _write_atomic(os.path.join(folder, "trial.json"), json.dumps(
                {"status": "failed", "reason": f"fairgrasp train exited with {proc.returncode}: {' '.join(tail)}",
                 "wall_s": round(wall, 2)}, indent=1))
            raise RuntimeError(f"trial {name}: fairgrasp train exited with {proc.returncode}: {' / '.join(tail)}")
        with open(os.path.join(run_dir, "eval.json")) as f:
            final = json.load(f)
        status = "completed"
        _write_atomic(os.path.join(folder, "trial.json"), json.dumps(
            {"status": "completed", "reason": f"trained its {reported} evaluations to the end",
             "wall_s": round(wall, 2), "final": {k: final[k] for k in
                                                ("episodes", "successes", "success_rate", "ci_low", "ci_high")}},
            indent=1))
    finally:
        # Stopped by Tune (or an error): end the training before the trial's process goes.
        code = terminate(proc)
        if status != "completed" and status != "failed":
            _write_atomic(os.path.join(folder, "stopped.json"), json.dumps(
                {"exit": code, "after_s": round(time.time() - start, 2), "evaluations_reported": reported}))


# ---------------------------------------------------------------------------------------------
# The sweep (runs in the driver).


def _recording_asha(log_path, **kwargs):
    """ASHA that appends each decision to stop a trial (trial, evaluations, success, the rung's
    cutoff) to ``log_path`` (a file: the scheduler object may be copied by Tune)."""
    from ray.tune.schedulers import ASHAScheduler, TrialScheduler

    class RecordingASHA(ASHAScheduler):
        def on_trial_result(self, tune_controller, trial, result):
            decision = super().on_trial_result(tune_controller, trial, result)
            if decision == TrialScheduler.STOP:
                rung = None
                for bracket in self._brackets:
                    for milestone, recorded in bracket._rungs:
                        if result["evaluations"] >= milestone and recorded:
                            vals = list(recorded.values())
                            rung = {"milestone": milestone, "cutoff": bracket.cutoff(recorded), "trials_at_rung": len(vals)}
                            break
                with open(log_path, "a") as f:
                    f.write(json.dumps({"trial": result.get("trial"), "evaluations": result["evaluations"],
                                        METRIC: result[METRIC], "timesteps": result.get("timesteps"),
                                        "rung": rung}) + "\n")
            return decision

    return RecordingASHA(**kwargs)


def _expected_evaluations(config):
    per_update = int(config.get("n_envs", 8)) * int(config.get("ppo", {}).get("n_steps", 128))
    updates = math.ceil(int(config.get("total_timesteps", 1)) / max(1, per_update))
    return max(1, updates // max(1, int(config.get("eval_every", 10))))


def _moved_aside(path):
    n = 1
    while os.path.exists(f"{path}.replaced-{n}"):
        n += 1
    os.rename(path, f"{path}.replaced-{n}")
    return f"{path}.replaced-{n}"


def sweep(recipe, out, *, seeds=(0,), grid=None, fixed=None, binary=None, cpus_per_trial=None,
          num_cpus=None, grace_period=1, reduction_factor=2, address=None, force=False, poll_s=0.5,
          verbose=0):
    """Trains ``recipe`` for every seed × combination of ``grid`` (``{"ppo.learning_rate": [..],
    ...}``), each with ``fixed`` overrides, as Ray Tune trials under ASHA on ``eval_success``.
    Returns the table (also in ``out/sweep.json``): ``trials`` (one dict per trial), ``best``,
    ``wall_s``, ``out``. ``cpus_per_trial``: the CPUs Tune reserves per trial (default: the
    config's ``threads``); ``num_cpus``: of the local Ray instance started here when Ray is not
    running yet (``address``: an existing cluster). ``force``: an ``out`` that holds files is moved
    aside to ``out.replaced-N`` (never deleted); without it such an ``out`` is refused."""
    seeds = list(seeds)
    if not seeds or any(not isinstance(s, int) or isinstance(s, bool) or not 0 <= s <= 2**53 - 1 for s in seeds):
        raise SweepError(f"seeds {seeds}: give one or more integers in 0–9007199254740991")
    if len(set(seeds)) != len(seeds):
        raise SweepError(f"seeds {seeds}: a seed is given twice")
    grid = dict(grid or {})
    fixed = dict(fixed or {})
    for key, values in grid.items():
        if not isinstance(values, (list, tuple)) or not values:
            raise SweepError(f"grid {key}: give a non-empty list of values, not {values!r}")
        if key in fixed or key == "seed":
            raise SweepError(f"grid {key}: also fixed or the seed (sweep seeds with seeds=)")
    if "seed" in fixed:
        raise SweepError("fixed seed: give the seeds with seeds=")
    combos = [dict(zip(grid, values)) for values in itertools.product(*grid.values())]
    if len(seeds) * len(combos) > MAX_TRIALS:
        raise SweepError(f"{len(seeds)} seeds × {len(combos)} combinations = {len(seeds) * len(combos)} trials: "
                         f"at most {MAX_TRIALS}")
    if not (isinstance(grace_period, int) and grace_period >= 1):
        raise SweepError(f"grace_period {grace_period!r}: evaluations before ASHA may stop a trial, an integer ≥ 1")
    if not (isinstance(reduction_factor, (int, float)) and 1 < reduction_factor <= 100):
        raise SweepError(f"reduction_factor {reduction_factor!r}: must be in (1, 100]")
    if not (isinstance(poll_s, (int, float)) and 0.01 <= poll_s <= 60):
        raise SweepError(f"poll_s {poll_s!r}: must be in 0.01–60 s")
    binary = find_binary(binary)
    with open(recipe_path(recipe), "rb") as f:
        base = tomllib.load(f)
    for key, value in fixed.items():
        set_key(base, key, value)

    # Every trial's config checked by the binary before Ray starts.
    configs = {}
    with tempfile.TemporaryDirectory(prefix="fairgrasp-tune-configs-") as scratch:
        for seed in seeds:
            for combo in combos:
                name = trial_name(seed, combo)
                config = trial_config(base, seed, combo)
                path = os.path.join(scratch, name + ".toml")
                _write_atomic(path, to_toml(config))
                check_config(binary, path, name)
                configs[name] = config
    out = os.path.abspath(os.fspath(out))
    if os.path.exists(out) and (not os.path.isdir(out) or os.listdir(out)):
        if not force:
            raise SweepError(f"out {out}: holds files (a sweep's?); choose a new folder or pass force=True "
                             "(--force) to move it aside")
        _moved_aside(out)
    os.makedirs(out, exist_ok=True)
    trials_dir = os.path.join(out, "trials")
    os.makedirs(trials_dir, exist_ok=True)

    if cpus_per_trial is None:
        cpus_per_trial = max(int(c.get("threads", 1)) for c in configs.values())
    if not (isinstance(cpus_per_trial, (int, float)) and 0 < cpus_per_trial <= 1024):
        raise SweepError(f"cpus_per_trial {cpus_per_trial!r}: must be in (0, 1024]")
    max_t = max(_expected_evaluations(c) for c in configs.values()) + 1
    if grace_period > max_t:
        raise SweepError(f"grace_period {grace_period}: more than the {max_t - 1} evaluations a trial makes")

    import ray
    from ray import tune

    if not ray.is_initialized():
        ray.init(address=address, num_cpus=None if address else num_cpus, include_dashboard=False,
                 log_to_driver=verbose > 0)
    decisions = os.path.join(out, "asha_stops.jsonl")
    open(decisions, "w").close()
    scheduler = _recording_asha(decisions, time_attr="evaluations", max_t=max_t, grace_period=grace_period,
                                reduction_factor=reduction_factor)
    trainable = tune.with_resources(
        tune.with_parameters(_trial, base=base, binary=binary, trials_dir=trials_dir, poll_s=float(poll_s)),
        {"cpu": cpus_per_trial},
    )
    param_space = {"seed": tune.grid_search(seeds)}
    if grid:
        param_space["set"] = {k: tune.grid_search(list(v)) for k, v in grid.items()}
    start = time.time()
    tuner = tune.Tuner(
        trainable,
        param_space=param_space,
        tune_config=tune.TuneConfig(metric=METRIC, mode="max", scheduler=scheduler, num_samples=1,
                                    reuse_actors=False),
        run_config=tune.RunConfig(storage_path=out, name="tune", verbose=verbose,
                                  failure_config=tune.FailureConfig(max_failures=0)),
    )
    results = tuner.fit()
    wall = time.time() - start

    stops = {}
    with open(decisions) as f:
        for line in f:
            d = json.loads(line)
            stops[d["trial"]] = d
    rows = []
    for result in results:
        seed, combo = result.config["seed"], dict(result.config.get("set", {}))
        name = trial_name(seed, combo)
        folder = os.path.join(trials_dir, name)
        reported = []
        df = result.metrics_dataframe
        if df is not None and METRIC in df:
            reported = [float(v) for v in df[METRIC].dropna()]
        info = {}
        if os.path.exists(os.path.join(folder, "trial.json")):
            with open(os.path.join(folder, "trial.json")) as f:
                info = json.load(f)
        # A training still running (its trial's process went without terminating it): end it.
        pid_file = os.path.join(folder, "pid")
        leftover = False
        if os.path.exists(pid_file):
            with open(pid_file) as f:
                pid = int(f.read())
            leftover = _alive_child(pid, binary)
            if leftover:
                os.kill(pid, signal.SIGKILL)
        if name in stops and info.get("status") != "completed":
            stop = stops[name]
            rung = stop.get("rung") or {}
            status = "stopped by ASHA"
            reason = (f"after {stop['evaluations']} evaluations ({stop['timesteps']} steps) its success "
                      f"{stop[METRIC]:.3f} was below the cutoff {rung.get('cutoff')} of ASHA's rung at "
                      f"{rung.get('milestone', float('nan')):g} evaluations ({rung.get('trials_at_rung')} trials there)")
            ended = _read_json(os.path.join(folder, "stopped.json"))
            if ended:
                reason += f"; its training was ended (exit status {ended['exit']}) after {ended['after_s']} s"
            else:
                # Ray ended the trial's process before its `finally` wrote stopped.json: the
                # training got SIGTERM from the kernel (PR_SET_PDEATHSIG); its exit status is lost.
                reason += f"; {ENDED_WITH_ITS_TRIAL}"
        elif info:
            status, reason = info["status"], info["reason"]
        else:
            status = "failed" if result.error else "unknown"
            reason = str(result.error) if result.error else "no record"
        events = sorted(f for f in os.listdir(os.path.join(folder, "run")) if f.startswith("events.out.tfevents")) \
            if os.path.isdir(os.path.join(folder, "run")) else []
        rows.append({
            "trial": name, "seed": seed, "set": combo, "status": status, "reason": reason,
            "evaluations": len(reported), "reported": reported,
            "best_success": max(reported) if reported else None,
            "last_success": reported[-1] if reported else None,
            "final": info.get("final"), "wall_s": info.get("wall_s", _wall_of(folder)),
            "run_dir": os.path.join(folder, "run"), "event_files": events,
            "left_running": leftover,
        })
    rows.sort(key=lambda r: (json.dumps(r["set"], sort_keys=True), r["seed"]))
    scored = [r for r in rows if r["best_success"] is not None]
    best = max(scored, key=lambda r: r["best_success"]) if scored else None
    tune_best = None
    try:
        b = results.get_best_result(metric=METRIC, mode="max", scope="all")
        tune_best = trial_name(b.config["seed"], dict(b.config.get("set", {})))
    except RuntimeError:
        pass
    table = {
        "recipe": recipe, "out": out, "binary": binary, "seeds": seeds, "grid": grid, "fixed": fixed,
        "scheduler": {"name": "ASHA", "metric": METRIC, "time_attr": "evaluations", "grace_period": grace_period,
                      "reduction_factor": reduction_factor, "max_t": max_t},
        "cpus_per_trial": cpus_per_trial, "ray_cpus": ray.cluster_resources().get("CPU"),
        "wall_s": round(wall, 2), "trials": rows,
        "best": None if best is None else {"trial": best["trial"], "seed": best["seed"], "set": best["set"],
                                           "best_success": best["best_success"], "tune_best_trial": tune_best},
    }
    _write_atomic(os.path.join(out, "sweep.json"), json.dumps(table, indent=1))
    _write_atomic(os.path.join(out, "sweep.md"), format_table(table))
    return table


#: The reason's ending for a stopped trial whose training's exit was not recorded.
ENDED_WITH_ITS_TRIAL = "its training was ended with its trial's process (exit status not recorded)"


def _alive_child(pid, binary):
    """Whether ``pid`` is still a running ``fairgrasp`` process (not a reused pid)."""
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            cmd = f.read().split(b"\0")
        with open(f"/proc/{pid}/stat") as f:
            state = f.read().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z" and bool(cmd) and os.path.basename(cmd[0].decode()) == os.path.basename(binary)


def _read_json(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def _wall_of(folder):
    stopped = os.path.join(folder, "stopped.json")
    if os.path.exists(stopped):
        with open(stopped) as f:
            return json.load(f).get("after_s")
    return None


def _pct(v):
    return "–" if v is None else f"{100 * v:.1f} %"


def format_table(table):
    """The sweep as Markdown: one row per trial, then the best config and the wall time."""
    keys = list(table["grid"])
    head = ["trial", "seed"] + keys + ["status", "evaluations", "best", "last", "final (eval.json)", "wall s"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in table["trials"]:
        final = r["final"]
        final_s = "–" if not final else (f"{final['successes']}/{final['episodes']} = {_pct(final['success_rate'])} "
                                         f"({100 * final['ci_low']:.1f}–{100 * final['ci_high']:.1f})")
        cells = [r["trial"], str(r["seed"])] + [str(r["set"].get(k)) for k in keys] + [
            r["status"], str(r["evaluations"]), _pct(r["best_success"]), _pct(r["last_success"]), final_s,
            "–" if r["wall_s"] is None else f"{r['wall_s']:.1f}"]
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    for r in table["trials"]:
        lines.append(f"- {r['trial']}: {r['status']}: {r['reason']}")
    best = table["best"]
    lines.append("")
    lines.append(f"Best: {best['trial']} (seed {best['seed']}, {best['set']}), {_pct(best['best_success'])} at its "
                 f"best evaluation." if best else "Best: none (no trial reported an evaluation).")
    lines.append(f"Wall time: {table['wall_s']:.1f} s on {table['ray_cpus']} CPUs, {table['cpus_per_trial']} per trial.")
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python -m fairgrasp.tune",
        description="A sweep of Rust PPO trainings (fairgrasp train) as Ray Tune trials: seeds × a grid of "
                    "recipe overrides, ASHA on the held-out evaluation success. Writes OUT/trials/<trial>/run "
                    "(each run folder), OUT/sweep.json and OUT/sweep.md (the table).")
    parser.add_argument("recipe", help="a shipped recipe (e.g. residual_miscalibrated) or a training config's path")
    parser.add_argument("--out", required=True, help="the sweep folder (new or empty; --force moves an old one aside)")
    parser.add_argument("--seeds", type=int, nargs="+", default=[0], help="training seeds (default 0)")
    parser.add_argument("--grid", action="append", default=[], metavar="KEY=V1,V2,...",
                        help="an override swept over its values (repeat for a grid), e.g. ppo.learning_rate=3e-4,1e-3")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="an override every trial gets, e.g. preset=nudged, total_timesteps=100000")
    parser.add_argument("--bin", default=None, help="the fairgrasp binary built with --features train "
                                                    "(default: $FAIRGRASP_BIN, else fairgrasp on PATH)")
    parser.add_argument("--cpus", type=int, default=None, help="CPUs of the local Ray instance (default: all)")
    parser.add_argument("--cpus-per-trial", type=float, default=None, help="CPUs per trial (default: the config's threads)")
    parser.add_argument("--grace-period", type=int, default=1, help="evaluations before ASHA may stop a trial")
    parser.add_argument("--reduction-factor", type=float, default=2.0, help="ASHA's reduction factor")
    parser.add_argument("--address", default=None, help="an existing Ray cluster (e.g. auto)")
    parser.add_argument("--force", action="store_true", help="move an --out that holds files aside to OUT.replaced-N")
    parser.add_argument("--verbose", type=int, default=0, choices=[0, 1, 2], help="Tune's console output")
    args = parser.parse_args(argv)
    try:
        grid = dict(parse_assignment(g, many=True) for g in args.grid)
        fixed = dict(parse_assignment(s) for s in args.set)
        table = sweep(args.recipe, args.out, seeds=args.seeds, grid=grid, fixed=fixed, binary=args.bin,
                      num_cpus=args.cpus, cpus_per_trial=args.cpus_per_trial, grace_period=args.grace_period,
                      reduction_factor=args.reduction_factor, address=args.address, force=args.force,
                      verbose=args.verbose)
    except SweepError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except ModuleNotFoundError as e:
        if e.name == "ray":
            print('error: Ray Tune is not installed: pip install "ray[tune]==2.60.0"', file=sys.stderr)
            return 2
        raise
    print(format_table(table), end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
