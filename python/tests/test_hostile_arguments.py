"""A seeded fuzz of the Python API's arguments (issue 50): hostile values (megabyte strings,
paths to devices and FIFOs, huge and non-finite numbers, wrong types, nested tables) given to
every entry point that reads them. Each call returns or raises an ordinary exception (never
pyo3's PanicException, a BaseException), within a minute (a hang dumps the stacks and fails the
run), and an exception's message is bounded like the CLI's (2000 characters and a note)."""

import faulthandler
import os
import random

import pytest

import fairgrasp
from fairgrasp import kinematics

# fairgrasp_types::text::MAX_MESSAGE_CHARS and the length note after it.
MAX_MESSAGE = 2000 + 40
CALLS = 400


@pytest.fixture(scope="module")
def fifo(tmp_path_factory):
    path = tmp_path_factory.mktemp("hostile") / "nobody_writes.toml"
    os.mkfifo(path)
    return str(path)


def hostile_values(fifo):
    return [
        "",
        "x" * 1_000_000,
        "a b " * 100_000,
        "full\n" * 10_000,
        "../../etc/passwd",
        "/dev/zero",
        fifo,
        "\x00",
        "ü" * 5_000,
        -1,
        0,
        2**64,
        10**12,
        -(2**63),
        float("nan"),
        float("inf"),
        -0.5,
        None,
        [],
        [float("nan")] * 6,
        [1e308] * 7,
        {"x" * 100_000: 1},
        {"env": {"task": {"max_steps": -5}}},
        {"mode": "pure", "residual_scale": 0.5},
        b"bytes",
        object(),
    ]


def entry_points(tmp):
    """Each entry point as a function of one hostile value."""
    return {
        "FairGraspEnv(preset=)": lambda v: fairgrasp.FairGraspEnv(preset=v),
        "FairGraspEnv(arm=)": lambda v: fairgrasp.FairGraspEnv(arm=v),
        "FairGraspEnv(config_toml=)": lambda v: fairgrasp.FairGraspEnv(config_toml=v),
        "make(recipe)": lambda v: fairgrasp.make(v),
        "make(agent=)": lambda v: fairgrasp.make("residual_miscalibrated", agent=v),
        "make(env=)": lambda v: fairgrasp.make("residual_miscalibrated", env=v),
        "make(preset=)": lambda v: fairgrasp.make("pure_full", preset=v),
        "VectorEnv(num_envs=)": lambda v: fairgrasp.VectorEnv(num_envs=v, preset="fixed"),
        "VectorEnv(threads=)": lambda v: fairgrasp.VectorEnv(num_envs=2, threads=v, preset="fixed"),
        "Baseline(preset=)": lambda v: fairgrasp.Baseline(preset=v),
        "load_policy": lambda v: fairgrasp.load_policy(v),
        "evaluate(episodes=)": lambda v: fairgrasp.evaluate("residual_hard", preset="fixed", episodes=v),
        "train(config)": lambda v: fairgrasp.train(v, str(tmp / "run")),
        "fk": lambda v: kinematics.fk(v),
        "ik": lambda v: kinematics.ik(v),
        "Chain(urdf)": lambda v: kinematics.Chain(v),
        "world_to_base": lambda v: kinematics.world_to_base(v, [0.0, 0.0, 0.0]),
        "calibrate_points": lambda v: kinematics.calibrate_points(v, v),
    }


def close(result):
    if hasattr(result, "close"):
        result.close()


def test_hostile_arguments_raise_bounded_ordinary_exceptions(fifo, tmp_path):
    values = hostile_values(fifo)
    points = entry_points(tmp_path)
    names = sorted(points)
    rng = random.Random(50)
    faulthandler.dump_traceback_later(60, exit=True)
    seen = {"returned": 0, "raised": 0}
    try:
        for k in range(CALLS):
            name = names[rng.randrange(len(names))]
            value = values[rng.randrange(len(values))]
            shown = f"call {k}: {name}({type(value).__name__} {repr(value)[:60]})"
            faulthandler.dump_traceback_later(60, exit=True)
            try:
                close(points[name](value))
                seen["returned"] += 1
            except Exception as e:  # an ordinary exception; a panic is a BaseException
                seen["raised"] += 1
                message = str(e)
                assert len(message) <= MAX_MESSAGE, f"{shown}: {len(message)} characters: {message[:200]}…"
            except BaseException as e:
                pytest.fail(f"{shown}: {type(e).__name__}: {str(e)[:300]}")
    finally:
        faulthandler.cancel_dump_traceback_later()
    # Most hostile values are refused; a few (0, "", None for a default) are fine.
    assert seen["raised"] > CALLS // 2, seen
    assert not (tmp_path / "run").exists(), "a refused training left a run folder"
