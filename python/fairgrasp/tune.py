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
highest success any evaluation reported. A failed trial's reason is the trainer's own message
(``fairgrasp train failed (exit status 1) after 2 evaluations: update 5 failed: … diverged …``)
or the signal that killed it.

A killed sweep (or one ended by Ctrl-C) continues with ``resume=True`` (``--resume``) and the same
arguments: the request in ``<out>/sweep_request.json`` must match (a recipe, seed, grid, fixed
value or ASHA setting that differs is refused by name), finished trials (completed, failed by the
trainer's own error, stopped by ASHA) are kept untouched, and the others run again, each
continuing from its run folder's last checkpoint (``fairgrasp train --resume``), in a new Tune
experiment (``<out>/tune-resume-N``). ASHA's rungs then hold only the trials that run again.

Every argument, and every trial config (by the binary: a misspelt key or a bad value is refused
naming the trial, with the binary's message), is checked before Ray starts. Needs ``pip install
"ray[tune]==2.60.0"``.
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
            raise SweepError(f"recipe {recipe}: {'not a regular file' if os.path.exists(recipe) else 'no such file'}")
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


_DOTTED_KEY = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)*")


def check_key(where, key):
    """Refuses (SweepError naming ``where``) anything but a dotted recipe key (``ppo.learning_rate``)."""
    if not isinstance(key, str) or not _DOTTED_KEY.fullmatch(key):
        raise SweepError(f"{where}: not a dotted recipe key such as ppo.learning_rate")


def parse_assignment(text, *, many=False):
    """``key=value`` (``many``: ``key=v1,v2,...``; a TOML array as one value needs ``key=[..]``
    with ``many`` off) → (dotted key, value or list of values)."""
    key, sep, value = text.partition("=")
    key = key.strip()
    if not sep or not _DOTTED_KEY.fullmatch(key) or not value.strip():
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
    """One Tune trial: trains its config (resuming its run folder when that holds a checkpoint,
    as after a killed sweep), reports each evaluation of ``metrics.csv`` to Tune, and records how
    it ended in ``trial.json`` (completed, or failed with the trainer's own message) or
    ``stopped.json`` (stopped by Tune)."""
    seed, overrides = config["trial"]["seed"], dict(config["trial"]["set"])
    name = trial_name(seed, overrides)
    folder = os.path.join(trials_dir, name)
    run_dir = os.path.join(folder, "run")
    os.makedirs(folder, exist_ok=True)
    config_path = os.path.join(folder, "config.toml")
    _write_atomic(config_path, to_toml(trial_config(base, seed, overrides)))
    for stale in ("trial.json", "stopped.json"):  # an earlier attempt's (a trainer killed by a signal)
        if os.path.exists(os.path.join(folder, stale)):
            os.replace(os.path.join(folder, stale), os.path.join(folder, stale + ".earlier"))
    command = [binary, "train", "--config", config_path, "--run-dir", run_dir]
    if os.path.isdir(os.path.join(run_dir, "checkpoints", "latest")):
        command.append("--resume")
    start, log_path = time.time(), os.path.join(folder, "train.log")
    with open(log_path, "a") as log:  # appended: an earlier attempt's log stays
        log.write(f"--- {time.strftime('%Y-%m-%d %H:%M:%S')}: {' '.join(command[1:])}\n")
        log.flush()
        log_start = log.tell()
        proc = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, preexec_fn=_die_with_parent)
    _write_atomic(os.path.join(folder, "pid"), f"{proc.pid}\n")
    ended, reported = None, 0
    try:
        reported = _follow(proc, run_dir, name, poll_s)
        if reported is None:
            ended = "stopped"
            return
        _record_end(folder, proc.returncode, reported, time.time() - start, run_dir, log_path, log_start)
        ended = "recorded"
    except Exception as e:  # the trainer's failure (trial.json written) or the trial's own
        if not os.path.exists(os.path.join(folder, "trial.json")):
            _write_atomic(os.path.join(folder, "trial.json"), json.dumps(
                {"status": "failed", "reason": f"the trial itself failed: {type(e).__name__}: {e}",
                 "exit": None, "evaluations": reported or 0, "wall_s": round(time.time() - start, 2)}, indent=1))
        ended = "recorded"
        raise
    finally:
        # Stopped by Tune (or an error): end the training before the trial's process goes.
        code = terminate(proc)
        if ended != "recorded":
            _write_atomic(os.path.join(folder, "stopped.json"), json.dumps(
                {"exit": code, "after_s": round(time.time() - start, 2), "evaluations_reported": reported}))


def _follow(proc, run_dir, name, poll_s):
    """Reports each new evaluation row of the run's ``metrics.csv`` to Tune until the training
    exits (returns the number reported) or Tune asks the trial to stop (returns None)."""
    from ray import tune

    offset, header, reported = 0, None, 0
    while True:
        exited = proc.poll() is not None
        rows, offset, header = read_evaluations(os.path.join(run_dir, "metrics.csv"), offset, header)
        for row in rows:
            reported += 1
            tune.report({**row, "evaluations": reported, "trial": name})
        if exited:
            return reported
        if _stop_requested():
            return None
        time.sleep(poll_s)


def _record_end(folder, code, reported, wall, run_dir, log_path, log_start):
    """Writes ``trial.json`` for a training that exited by itself: completed (with its final
    evaluation, ``eval.json``), or failed with its reason (raised too, so Tune marks it)."""
    if code != 0:
        reason = failure_reason(code, reported, _log_since(log_path, log_start))
        _write_atomic(os.path.join(folder, "trial.json"), json.dumps(
            {"status": "failed", "reason": reason, "exit": code, "evaluations": reported,
             "wall_s": round(wall, 2)}, indent=1))
        raise RuntimeError(f"trial {os.path.basename(folder)}: {reason}")
    with open(os.path.join(run_dir, "eval.json")) as f:
        final = json.load(f)
    _write_atomic(os.path.join(folder, "trial.json"), json.dumps(
        {"status": "completed", "reason": f"trained its {reported} evaluations to the end", "exit": 0,
         "evaluations": reported, "wall_s": round(wall, 2),
         "final": {k: final[k] for k in ("episodes", "successes", "success_rate", "ci_low", "ci_high")}},
        indent=1))


def _log_since(path, offset):
    """What ``path`` holds from byte ``offset`` on (the last 64 kB), as text."""
    with open(path, "rb") as f:
        f.seek(max(offset, os.path.getsize(path) - 65536))
        return f.read().decode(errors="replace")


def failure_reason(code, evaluations, log_text):
    """Why a training ended with exit status ``code`` (negative: the signal that killed it), in
    words: the trainer's own ``error: …`` message when it printed one, else the log's last
    lines."""
    if code < 0:
        try:
            signame = signal.Signals(-code).name
        except ValueError:
            signame = "an unknown signal"
        return (f"fairgrasp train was killed by {signame} (signal {-code}) after {evaluations} evaluations, "
                "from outside the sweep (the OOM killer, a user); its run folder keeps its last checkpoint, "
                "and a resumed sweep (--resume) continues it")
    lines = [line.strip() for line in log_text.splitlines() if line.strip()]
    errors = [line[len("error:"):].strip() for line in lines if line.startswith("error:")]
    said = errors[-1] if errors else (" / ".join(lines[-3:]) or "it printed nothing")
    return f"fairgrasp train failed (exit status {code}) after {evaluations} evaluations: {said}"


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
    """The evaluations a training of ``config`` makes: one every ``eval_every`` updates and one
    after the last update (``rl/src/run/train.rs``), so ⌈updates / eval_every⌉."""
    per_update = int(config.get("n_envs", 8)) * int(config.get("ppo", {}).get("n_steps", 128))
    updates = math.ceil(int(config.get("total_timesteps", 1)) / max(1, per_update))
    return max(1, math.ceil(updates / max(1, int(config.get("eval_every", 10)))))


def _moved_aside(path):
    n = 1
    while os.path.exists(f"{path}.replaced-{n}"):
        n += 1
    os.rename(path, f"{path}.replaced-{n}")
    return f"{path}.replaced-{n}"


#: The sweep's request, written into OUT when it starts: what a resumed sweep (``resume=True``,
#: ``--resume``) must ask for again.
REQUEST_FILE = "sweep_request.json"
#: The largest recipe read [bytes] (the trainer's own bound, ``MAX_CONFIG_BYTES``).
MAX_RECIPE_BYTES = 1 << 20


def sweep(recipe, out, *, seeds=(0,), grid=None, fixed=None, binary=None, cpus_per_trial=None,
          num_cpus=None, grace_period=1, reduction_factor=2, address=None, force=False, resume=False,
          poll_s=0.5, verbose=0):
    """Trains ``recipe`` for every seed × combination of ``grid`` (``{"ppo.learning_rate": [..],
    ...}``), each with ``fixed`` overrides, as Ray Tune trials under ASHA on ``eval_success``.
    Returns the table (also in ``out/sweep.json``): ``trials`` (one dict per trial), ``best``,
    ``wall_s``, ``out``. ``cpus_per_trial``: the CPUs Tune reserves per trial (default: the
    config's ``threads``); ``num_cpus``: of the local Ray instance started here when Ray is not
    running yet (``address``: an existing cluster). ``force``: an ``out`` that holds files is moved
    aside to ``out.replaced-N`` (never deleted); without it such an ``out`` is refused.
    ``resume``: continue the sweep in ``out`` (killed, or ended by Ctrl-C): the same request is
    required (anything that differs is refused by name), its finished trials (completed, failed by
    the trainer's own error, stopped by ASHA) are kept as they are, and the others run again,
    each continuing its run folder's last checkpoint. Every argument, and every trial's config
    (by the binary), is checked before Ray starts."""
    request = _checked_request(recipe, seeds, grid, fixed, grace_period, reduction_factor, poll_s,
                               verbose, num_cpus, force, resume)
    binary = find_binary(binary)
    base = read_recipe(request["recipe"])
    for key, value in request["fixed"].items():
        set_key(base, key, value)
    request["config"] = base
    trials = _checked_trials(binary, base, request["seeds"], request["grid"])
    cpus_per_trial = _checked_cpus(cpus_per_trial, trials, num_cpus, address)
    max_t = max(_expected_evaluations(t["config"]) for t in trials.values()) + 1
    if grace_period > max_t:
        raise SweepError(f"grace_period {grace_period}: more than the {max_t - 1} evaluations a trial makes")
    out = os.path.abspath(os.fspath(out))
    _prepare_out(out, request, force, resume)
    trials_dir = os.path.join(out, "trials")
    os.makedirs(trials_dir, exist_ok=True)
    stops = _read_stops(os.path.join(out, "asha_stops.jsonl"))
    kept = {name: row for name, t in trials.items() if (row := _finished_row(name, t, trials_dir, stops, binary))}
    pending = [t for name, t in trials.items() if name not in kept]
    scheduler = {"name": "ASHA", "metric": METRIC, "time_attr": "evaluations", "grace_period": grace_period,
                 "reduction_factor": reduction_factor, "max_t": max_t}
    start = time.time()
    results, ray_cpus = [], None
    if pending:
        results, ray_cpus = _run_tune(pending, out, base, binary, scheduler, cpus_per_trial, num_cpus,
                                      address, poll_s, verbose)
    wall = time.time() - start
    stops = _read_stops(os.path.join(out, "asha_stops.jsonl"))
    rows = list(kept.values()) + [_result_row(r, trials, trials_dir, stops, binary) for r in results]
    rows.sort(key=lambda r: (json.dumps(r["set"], sort_keys=True), r["seed"]))
    table = {
        "recipe": os.fspath(recipe), "out": out, "binary": binary,
        "seeds": request["seeds"], "grid": request["grid"], "fixed": request["fixed"], "scheduler": scheduler,
        "cpus_per_trial": cpus_per_trial, "ray_cpus": ray_cpus, "wall_s": round(wall, 2),
        "kept": len(kept), "trials": rows, "best": _best(rows, results),
    }
    _write_atomic(os.path.join(out, "sweep.json"), json.dumps(table, indent=1))
    _write_atomic(os.path.join(out, "sweep.md"), format_table(table))
    return table


def _checked_request(recipe, seeds, grid, fixed, grace_period, reduction_factor, poll_s, verbose, num_cpus,
                     force, resume):
    """The sweep's arguments checked (SweepError naming the argument, the value and what is
    allowed), as the request recorded in OUT: recipe path, seeds, grid, fixed, ASHA's settings."""
    try:
        seeds = list(seeds)
    except TypeError:
        raise SweepError(f"seeds {seeds!r}: give a list of integers") from None
    if not seeds or any(type(s) is not int or not 0 <= s <= 2**53 - 1 for s in seeds):
        raise SweepError(f"seeds {seeds}: give one or more integers in 0–9007199254740991")
    if len(set(seeds)) != len(seeds):
        raise SweepError(f"seeds {seeds}: a seed is given twice")
    grid, fixed = _checked_overrides("grid", grid), _checked_overrides("fixed", fixed)
    for key, values in grid.items():
        if not isinstance(values, (list, tuple)) or not values:
            raise SweepError(f"grid {key}: give a non-empty list of values, not {values!r}")
        if len({json.dumps(v, sort_keys=True) for v in values}) != len(values):
            raise SweepError(f"grid {key}: a value is given twice in {list(values)!r}")
        if key in fixed or key == "seed":
            raise SweepError(f"grid {key}: also fixed or the seed (sweep seeds with seeds=)")
    if "seed" in fixed:
        raise SweepError("fixed seed: give the seeds with seeds=")
    combos = math.prod(len(v) for v in grid.values())
    if len(seeds) * combos > MAX_TRIALS:
        raise SweepError(f"{len(seeds)} seeds × {combos} combinations = {len(seeds) * combos} trials: "
                         f"at most {MAX_TRIALS}")
    if not (type(grace_period) is int and grace_period >= 1):
        raise SweepError(f"grace_period {grace_period!r}: evaluations before ASHA may stop a trial, an integer ≥ 1")
    if not (type(reduction_factor) in (int, float) and 1 < reduction_factor <= 100):
        raise SweepError(f"reduction_factor {reduction_factor!r}: must be in (1, 100]")
    if not (type(poll_s) in (int, float) and 0.01 <= poll_s <= 60):
        raise SweepError(f"poll_s {poll_s!r}: must be in 0.01–60 s")
    if verbose not in (0, 1, 2) or type(verbose) is not int:
        raise SweepError(f"verbose {verbose!r}: must be 0, 1 or 2")
    if num_cpus is not None and not (type(num_cpus) is int and 1 <= num_cpus <= 4096):
        raise SweepError(f"num_cpus {num_cpus!r}: the local Ray instance's CPUs, an integer in 1–4096")
    if force and resume:
        raise SweepError("force and resume: choose one (force moves an old sweep aside, resume continues it)")
    return {"recipe": recipe_path(recipe), "seeds": seeds, "grid": json.loads(json.dumps(grid)),
            "fixed": json.loads(json.dumps(fixed)), "grace_period": grace_period,
            "reduction_factor": reduction_factor}


def _checked_overrides(what, overrides):
    """``grid`` or ``fixed`` as a dict whose keys are dotted recipe keys."""
    if overrides is None:
        return {}
    if not isinstance(overrides, dict):
        raise SweepError(f"{what} {overrides!r}: give a dict of dotted recipe keys (ppo.learning_rate) to values")
    for key in overrides:
        check_key(f"{what} {key!r}", key)
    return dict(overrides)


def read_recipe(path):
    """The recipe at ``path`` as a dict (SweepError naming the file when it is not a regular
    file of at most MAX_RECIPE_BYTES holding TOML)."""
    if not os.path.isfile(path):
        raise SweepError(f"recipe {path}: not a regular file")
    size = os.path.getsize(path)
    if size > MAX_RECIPE_BYTES:
        raise SweepError(f"recipe {path}: {size} bytes, more than the {MAX_RECIPE_BYTES} a recipe may have")
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
        raise SweepError(f"recipe {path}: not a TOML file: {e}") from None


def _checked_trials(binary, base, seeds, grid):
    """Every trial (``{name: {"seed", "set", "config"}}``) with its config checked by the binary."""
    combos = [dict(zip(grid, values)) for values in itertools.product(*grid.values())]
    trials = {}
    with tempfile.TemporaryDirectory(prefix="fairgrasp-tune-configs-") as scratch:
        for seed in seeds:
            for combo in combos:
                name = trial_name(seed, combo)
                config = trial_config(base, seed, combo)
                path = os.path.join(scratch, name + ".toml")
                _write_atomic(path, to_toml(config))
                check_config(binary, path, name)
                trials[name] = {"seed": seed, "set": combo, "config": config}
    return trials


def _checked_cpus(cpus_per_trial, trials, num_cpus, address):
    """The CPUs Tune reserves per trial (default: the configs' ``threads``), refused when no trial
    could ever start on the local Ray instance (Tune would wait for CPUs forever)."""
    if cpus_per_trial is None:
        cpus_per_trial = max(int(t["config"].get("threads", 1)) for t in trials.values())
    if not (type(cpus_per_trial) in (int, float) and 0 < cpus_per_trial <= 1024):
        raise SweepError(f"cpus_per_trial {cpus_per_trial!r}: must be in (0, 1024]")
    if address is None:
        import ray

        available = ray.cluster_resources().get("CPU", 0) if ray.is_initialized() else (num_cpus or os.cpu_count())
        if cpus_per_trial > available:
            raise SweepError(f"cpus_per_trial {cpus_per_trial:g}: more than the {available:g} CPUs of the local Ray "
                             "instance, so no trial could start (lower --cpus-per-trial, or --set threads=1)")
    return cpus_per_trial


def _prepare_out(out, request, force, resume):
    """A new sweep: ``out`` made (refused if it holds files, or moved aside with ``force``) and the
    request written into it. A resumed one: the request in ``out`` must be this one."""
    path = os.path.join(out, REQUEST_FILE)
    if resume:
        earlier = _read_json(path)
        if earlier is None:
            raise SweepError(f"out {out}: no sweep to resume (no readable {REQUEST_FILE}); start it without --resume")
        differences = request_differences({**earlier, "recipe": None}, {**request, "recipe": None})
        if differences:
            raise SweepError(f"out {out}: the sweep there was started with another request, so it is not resumed: "
                             + "; ".join(differences))
        return
    if os.path.exists(out) and (not os.path.isdir(out) or os.listdir(out)):
        if not force:
            raise SweepError(f"out {out}: holds files (a sweep's?); choose a new folder, pass resume=True "
                             "(--resume) to continue the sweep there, or force=True (--force) to move it aside")
        _moved_aside(out)
    os.makedirs(out, exist_ok=True)
    _write_atomic(path, json.dumps(request, indent=1))


def request_differences(earlier, now):
    """What differs between two sweep requests, one ``field: earlier → now`` per leaf (the
    recipe's config flattened to dotted keys)."""
    def flat(value, prefix):
        if isinstance(value, dict) and value:
            return {k: v for key, sub in value.items() for k, v in flat(sub, f"{prefix}.{key}").items()}
        return {prefix: value}
    a = flat(json.loads(json.dumps(earlier)), "")
    b = flat(json.loads(json.dumps(now)), "")
    return [f"{k[1:]}: {json.dumps(a.get(k, '(none)'))} → {json.dumps(b.get(k, '(none)'))}"
            for k in sorted(set(a) | set(b)) if a.get(k, "(none)") != b.get(k, "(none)")]


def _run_tune(pending, out, base, binary, scheduler, cpus_per_trial, num_cpus, address, poll_s, verbose):
    """Runs the ``pending`` trials as one Tune experiment (``OUT/tune``, or ``OUT/tune-resume-N``
    for a resumed sweep: an earlier run's records are never written over). Returns Tune's results
    and the Ray instance's CPUs."""
    import ray
    from ray import tune

    if not ray.is_initialized():
        ray.init(address=address, num_cpus=None if address else num_cpus, include_dashboard=False,
                 log_to_driver=verbose > 0)
    name, n = "tune", 0
    while os.path.exists(os.path.join(out, name)):
        n += 1
        name = f"tune-resume-{n}"
    settings = {k: scheduler[k] for k in ("max_t", "grace_period", "reduction_factor")}
    asha = _recording_asha(os.path.join(out, "asha_stops.jsonl"), time_attr="evaluations", **settings)
    trainable = tune.with_resources(
        tune.with_parameters(_trial, base=base, binary=binary, trials_dir=os.path.join(out, "trials"),
                             poll_s=float(poll_s)),
        {"cpu": cpus_per_trial},
    )
    tuner = tune.Tuner(
        trainable,
        param_space={"trial": tune.grid_search([{"seed": t["seed"], "set": t["set"]} for t in pending])},
        tune_config=tune.TuneConfig(metric=METRIC, mode="max", scheduler=asha, num_samples=1, reuse_actors=False),
        run_config=tune.RunConfig(storage_path=out, name=name, verbose=verbose,
                                  failure_config=tune.FailureConfig(max_failures=0)),
    )
    return tuner.fit(), ray.cluster_resources().get("CPU")


def _read_stops(path):
    """ASHA's decisions to stop a trial (``asha_stops.jsonl``), by trial; a torn last line (a
    killed sweep) is skipped."""
    stops = {}
    try:
        with open(path) as f:
            for line in f:
                try:
                    d = json.loads(line)
                    stops[d["trial"]] = d
                except (ValueError, KeyError, TypeError):
                    continue
    except FileNotFoundError:
        pass
    return stops


def _finished_row(name, trial, trials_dir, stops, binary):
    """The table row of a trial an earlier run of this sweep finished (completed, failed by the
    trainer's own error, or stopped by ASHA), or None if it must run (again): never started, or
    its training was ended by a signal (the sweep killed, the OOM killer)."""
    folder = os.path.join(trials_dir, name)
    info = _read_json(os.path.join(folder, "trial.json")) or {}
    finished = info.get("status") == "completed" or (info.get("status") == "failed" and (info.get("exit") or 0) > 0)
    if not finished and name not in stops:
        return None
    count = info.get("evaluations") if finished else stops[name]["evaluations"]
    rows, _, _ = read_evaluations(os.path.join(folder, "run", "metrics.csv"))
    reported = [r[METRIC] for r in rows][:count]
    return {**_trial_row(name, trial, folder, reported, stops, binary, None), "kept": True}


def _result_row(result, trials, trials_dir, stops, binary):
    """The table row of a trial this run trained, from Tune's result and the trial's records."""
    name = trial_name(result.config["trial"]["seed"], dict(result.config["trial"]["set"]))
    df = result.metrics_dataframe
    reported = [float(v) for v in df[METRIC].dropna()] if df is not None and METRIC in df else []
    return _trial_row(name, trials[name], os.path.join(trials_dir, name), reported, stops, binary, result.error)


def _trial_row(name, trial, folder, reported, stops, binary, error):
    """One trial's row: its config, status and reason, what Tune got, its final evaluation."""
    info = _read_json(os.path.join(folder, "trial.json")) or {}
    leftover = _end_leftover(folder, binary)
    if name in stops and info.get("status") != "completed":
        status, reason = "stopped by ASHA", _stop_reason(stops[name], folder)
    elif info:
        status, reason = info["status"], info["reason"]
    else:
        status = "failed" if error else "unknown"
        reason = _error_reason(error) if error else "no record (the sweep was ended before the trial?)"
    run = os.path.join(folder, "run")
    events = sorted(f for f in os.listdir(run) if f.startswith("events.out.tfevents")) if os.path.isdir(run) else []
    return {
        "trial": name, "seed": trial["seed"], "set": trial["set"], "status": status,
        "reason": reason, "evaluations": len(reported), "reported": reported,
        "best_success": max(reported) if reported else None, "last_success": reported[-1] if reported else None,
        "final": info.get("final"), "wall_s": info.get("wall_s", _wall_of(folder)), "run_dir": run,
        "event_files": events, "left_running": leftover, "kept": False,
    }


def _stop_reason(stop, folder):
    """Why ASHA stopped a trial, and how its training ended."""
    rung = stop.get("rung") or {}
    reason = (f"after {stop['evaluations']} evaluations ({stop['timesteps']} steps) its success "
              f"{stop[METRIC]:.3f} was below the cutoff {rung.get('cutoff')} of ASHA's rung at "
              f"{rung.get('milestone', float('nan')):g} evaluations ({rung.get('trials_at_rung')} trials there)")
    ended = _read_json(os.path.join(folder, "stopped.json"))
    if ended:
        return reason + f"; its training was ended (exit status {ended['exit']}) after {ended['after_s']} s"
    # Ray ended the trial's process before its `finally` wrote stopped.json: the training got
    # SIGTERM from the kernel (PR_SET_PDEATHSIG); its exit status is lost.
    return reason + f"; {ENDED_WITH_ITS_TRIAL}"


def _error_reason(error):
    """Tune's error of a trial that left no record, as one line: its last non-empty line."""
    lines = [line.strip() for line in str(error).splitlines() if line.strip()]
    return (lines[-1] if lines else type(error).__name__)[:500]


def _end_leftover(folder, binary):
    """Kills the trial's training if it still runs (its trial's process went without ending it);
    returns whether it did."""
    pid_file = os.path.join(folder, "pid")
    if not os.path.exists(pid_file):
        return False
    try:
        with open(pid_file) as f:
            pid = int(f.read())
    except (OSError, ValueError):
        return False
    if _alive_child(pid, binary, os.path.join(folder, "run")):
        os.kill(pid, signal.SIGKILL)
        return True
    return False


def _best(rows, results):
    """The trial with the highest success any evaluation reported, and Tune's own best of the
    trials this run trained."""
    scored = [r for r in rows if r["best_success"] is not None]
    if not scored:
        return None
    best = max(scored, key=lambda r: r["best_success"])
    tune_best = None
    try:
        b = results.get_best_result(metric=METRIC, mode="max", scope="all") if results else None
        tune_best = b and trial_name(b.config["trial"]["seed"], dict(b.config["trial"]["set"]))
    except RuntimeError:
        pass
    return {"trial": best["trial"], "seed": best["seed"], "set": best["set"], "best_success": best["best_success"],
            "tune_best_trial": tune_best}


#: The reason's ending for a stopped trial whose training's exit was not recorded.
ENDED_WITH_ITS_TRIAL = "its training was ended with its trial's process (exit status not recorded)"


def _alive_child(pid, binary, run_dir):
    """Whether ``pid`` is still the running ``fairgrasp train`` of ``run_dir`` (not a reused pid,
    nor another training: a kept trial's pid file may be old)."""
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            cmd = f.read().split(b"\0")
        with open(f"/proc/{pid}/stat") as f:
            state = f.read().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return (state != "Z" and bool(cmd) and os.path.basename(cmd[0].decode(errors="replace")) == os.path.basename(binary)
            and os.fsencode(run_dir) in cmd)


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
        kept = " (kept from an earlier run of the sweep)" if r["kept"] else ""
        lines.append(f"- {r['trial']}: {r['status']}{kept}: {r['reason']}")
    best = table["best"]
    lines.append("")
    lines.append(f"Best: {best['trial']} (seed {best['seed']}, {best['set']}), {_pct(best['best_success'])} at its "
                 f"best evaluation." if best else "Best: none (no trial reported an evaluation).")
    lines.append(f"Wall time: {table['wall_s']:.1f} s on {table['ray_cpus']} CPUs, {table['cpus_per_trial']} per trial"
                 + (f"; {table['kept']} trials kept from an earlier run." if table["kept"] else "."))
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
    parser.add_argument("--resume", action="store_true",
                        help="continue the sweep in --out (killed or interrupted) with the same arguments: its "
                             "finished trials are kept, the others continue from their last checkpoint")
    parser.add_argument("--verbose", type=int, default=0, choices=[0, 1, 2], help="Tune's console output")
    args = parser.parse_args(argv)
    try:
        grid = dict(parse_assignment(g, many=True) for g in args.grid)
        fixed = dict(parse_assignment(s) for s in args.set)
        table = sweep(args.recipe, args.out, seeds=args.seeds, grid=grid, fixed=fixed, binary=args.bin,
                      num_cpus=args.cpus, cpus_per_trial=args.cpus_per_trial, grace_period=args.grace_period,
                      reduction_factor=args.reduction_factor, address=args.address, force=args.force,
                      resume=args.resume, verbose=args.verbose)
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
