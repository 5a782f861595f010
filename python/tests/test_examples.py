"""The examples and the package run on the package's oldest Python (``requires-python``): they
parse as Python 3.10 and import ``tomllib`` (3.11+) only with the ``tomli`` fallback; every
training example's reporting step runs on a lift and on a place preset."""

import ast
import importlib
import json
from pathlib import Path

import numpy as np
import pytest

import fairgrasp
from fairgrasp.compare import read_comparison, scripts_of, versus_script
from fairgrasp.recipes import task_residual_recipe

PYTHON = Path(__file__).resolve().parents[1]
SOURCES = sorted((PYTHON / "examples").glob("*.py")) + sorted((PYTHON / "fairgrasp").glob("*.py"))


def test_the_package_declares_python_3_10():
    assert 'requires-python = ">=3.10"' in (PYTHON / "pyproject.toml").read_text()


@pytest.mark.parametrize("path", SOURCES, ids=lambda p: p.name)
def test_every_source_parses_as_python_3_10_and_guards_tomllib(path):
    tree = ast.parse(path.read_text(), filename=str(path), feature_version=(3, 10))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import) and any(a.name == "tomllib" for a in node.names):
            guarded = [
                t for t in ast.walk(tree)
                if isinstance(t, ast.Try) and node in t.body
                and any(isinstance(i, ast.Import) and i.names[0].name == "tomli"
                        for h in t.handlers for i in h.body)
            ]
            assert guarded, f"{path.name}:{node.lineno}: `import tomllib` needs Python 3.11; add the tomli fallback"


# The reporting step of every training example on a lift and a place preset, with a stub model
# (no torch, SB3 or Ray here): the examples' modules are imported, their training never runs.

EXAMPLES = PYTHON / "examples"
LIFT, PLACE = "nudged", "place_tilted"


class StubModel:
    """SB3's ``predict`` interface: the zero action (for a residual, the script's own action),
    counting its calls."""

    def __init__(self, act_dim=7):
        self.act_dim, self.calls = act_dim, 0

    def predict(self, observation, state=None, episode_start=None, deterministic=True):
        self.calls += 1
        return np.zeros(self.act_dim), state


@pytest.fixture
def example(monkeypatch):
    """Imports an example module by name from python/examples (its siblings importable)."""
    monkeypatch.syspath_prepend(str(EXAMPLES))

    def load(name):
        return importlib.import_module(name)

    return load


def first_script(comparison, preset):
    """The first method of the comparison's run order without a policy folder on ``preset``."""
    by_name = {r["method"]: r for r in comparison["results"] if r["preset"] == preset}
    return next(by_name[m] for m in comparison["methods"] if m in by_name and by_name[m]["policy"] is None)


@pytest.mark.parametrize("preset, script", [(LIFT, "scripted baseline"), (PLACE, "place script")])
def test_sb3_residual_reports_against_the_tasks_open_loop_script(example, tmp_path, capsys, preset, script):
    sb3_residual = example("sb3_residual")
    out = tmp_path / "report"
    args = sb3_residual.parse_args(["--preset", preset, "--episodes", "4", "--out", str(out),
                                    "--log", str(tmp_path / "log.jsonl")])
    assert args.recipe == task_residual_recipe(preset)
    model = StubModel()
    row = sb3_residual.report(model, None, args, train_s=2.0)
    comparison = json.loads((out / "compare.json").read_text())
    assert model.calls > 0 and sb3_residual.NAME in comparison["methods"]
    assert row["script_name"] == first_script(comparison, preset)["method"] == script
    trained = next(r for r in comparison["results"] if r["method"] == sb3_residual.NAME)
    assert row["trained"] == trained["successes"] and row["episodes"] == 4
    assert json.loads((tmp_path / "log.jsonl").read_text()) == row
    printed = capsys.readouterr().out
    assert f"{script} (the task's open-loop script): " in printed and f"{out}/report.md" in printed


def test_sb3_residual_runs_the_issues_place_command(example, tmp_path):
    """``--recipe residual_place_tilted --preset place_tilted`` (issue 60: its report ended in a
    KeyError on the lift task's script name)."""
    sb3_residual = example("sb3_residual")
    args = sb3_residual.parse_args(["--recipe", "residual_place_tilted", "--preset", PLACE, "--episodes", "3",
                                    "--out", str(tmp_path / "report")])
    row = sb3_residual.report(StubModel(), None, args, train_s=1.0)
    assert row["recipe"] == "residual_place_tilted" and row["script_name"] == "place script"


def test_the_zero_residual_on_a_lift_preset_is_the_open_loop_script_episode_by_episode(example, tmp_path):
    sb3_residual = example("sb3_residual")
    out = tmp_path / "report"
    args = sb3_residual.parse_args(["--preset", LIFT, "--episodes", "6", "--out", str(out)])
    sb3_residual.report(StubModel(), None, args, train_s=1.0)
    comparison = json.loads((out / "compare.json").read_text())
    trained = next(r for r in comparison["results"] if r["method"] == sb3_residual.NAME)
    script = first_script(comparison, LIFT)
    assert [e["outcome"] for e in trained["results"]] == [e["outcome"] for e in script["results"]]
    assert [e["steps"] for e in trained["results"]] == [e["steps"] for e in script["results"]]


@pytest.mark.parametrize("preset, script", [(LIFT, "scripted baseline"), (PLACE, "place script")])
def test_rllib_ppo_reports_against_the_tasks_open_loop_script(example, tmp_path, preset, script):
    rllib_ppo = example("rllib_ppo")
    out = tmp_path / "report"
    args = rllib_ppo.parse_args(["--preset", preset, "--episodes", "3", "--out", str(out)])
    calls = []

    def act(obs):
        calls.append(obs.shape)
        return np.zeros(7)

    row = rllib_ppo.report(act, args, steps=1024, train_s=2.0)
    comparison = json.loads((out / "compare.json").read_text())
    assert calls and row["recipe"] == task_residual_recipe(preset)
    assert row["script_name"] == first_script(comparison, preset)["method"] == script
    assert rllib_ppo.NAME in comparison["methods"] and row["steps_per_s"] == 512.0


def test_sb3_pure_evaluates_on_lift_and_place_presets(example, tmp_path):
    sb3_pure = example("sb3_pure")
    args = sb3_pure.parse_args(["--presets", "fixed", "place", "--eval-episodes", "3",
                                "--log", str(tmp_path / "log.jsonl")])
    model = StubModel()
    row = sb3_pure.evaluation_row(model, None, args, {"timesteps": 0})
    assert model.calls > 0
    for preset in ("fixed", "place"):
        assert row[preset]["episodes"] == 3 and sum(row[preset]["outcomes"].values()) == 3
        assert row[preset + "_text"].startswith(f"{row[preset]['successes']}/3 = ")
    assert json.loads((tmp_path / "log.jsonl").read_text()) == row


@pytest.mark.parametrize("preset", ["sector", "place"])
def test_sb3_ppo_reports_on_lift_and_place_presets(example, preset):
    sb3_ppo = example("sb3_ppo")
    args = sb3_ppo.parse_args(["--preset", preset, "--episodes", "3"])
    model = StubModel()
    result = sb3_ppo.report(model, args)
    assert model.calls > 0 and result["preset"] == preset and result["episodes"] == 3


def test_versus_script_names_what_the_comparison_has(tmp_path):
    out = tmp_path / "report"
    fairgrasp.compare(policies={"still": lambda obs: np.zeros(7)}, presets=[PLACE], episodes=2, seed=3,
                      out=out, shipped=False)
    comparison = read_comparison(out)
    scripts = scripts_of(comparison, PLACE)
    assert [s["method"] for s in scripts] == [m for m in comparison["methods"] if m != "still"]
    pair = versus_script(comparison, "still", PLACE)
    # On a task with a takt the difference is of success within it.
    assert pair["method"]["takt_s"] is not None
    assert pair["difference_points"] == round(
        100 * (pair["method"]["within_takt_rate"] - pair["script"]["within_takt_rate"]), 1)
    with pytest.raises(ValueError, match=r"no 'SB3' on preset 'place_tilted': its methods are \["):
        versus_script(comparison, "SB3", PLACE)
    with pytest.raises(ValueError, match="its presets \\['place_tilted'\\]"):
        versus_script(comparison, "still", LIFT)
