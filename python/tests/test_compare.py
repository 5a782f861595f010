"""``fairgrasp.compare`` from Python writes ``fairgrasp compare``'s report folder with the Python
policies beside the scripts and the shipped policies, on the same scenarios; a bad policy is
refused naming it and leaves nothing in ``out``."""

import json

import numpy as np
import pytest

import fairgrasp


def test_python_policies_join_the_report_on_the_same_scenarios(tmp_path):
    out = tmp_path / "report"
    policy = fairgrasp.load_policy("residual_generalist")
    written = fairgrasp.compare(
        policies={"residual from Python": policy, "still": lambda obs: np.zeros(7)},
        presets=["nudged"], episodes=20, seed=5, out=out, threads=2)
    assert {"compare.json", "compare.csv", "report.ipynb", "report.md", "success_rate.png"} <= set(written)
    comparison = json.loads((out / "compare.json").read_text())
    assert comparison["methods"][-2:] == ["residual from Python", "still"]
    results = {r["method"]: r for r in comparison["results"]}
    ours, shipped = results["residual from Python"], results["residual PPO: residual_generalist"]
    # The same network on the same scenarios, once in Rust's compare and once from Python.
    assert [e["seed"] for e in ours["results"]] == [e["seed"] for e in shipped["results"]]
    assert [e["outcome"] for e in ours["results"]] == [e["outcome"] for e in shipped["results"]]
    assert results["still"]["successes"] == 0 and results["still"]["policy"].startswith("python")
    assert (out / "success_rate.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    notebook = json.loads((out / "report.ipynb").read_text())
    assert notebook["nbformat"] == 4 and notebook["cells"]
    assert "still" in (out / "report.md").read_text()
    # The paired tests pair each Python method with the scripts.
    assert "residual from Python" in (out / "report.md").read_text()


def test_a_bad_policy_or_name_is_refused_and_nothing_is_written(tmp_path):
    out = tmp_path / "report"

    def broken(obs):
        raise RuntimeError("sensor unplugged")

    with pytest.raises(fairgrasp.PolicyError, match="policy 'broken one' on preset 'sector'.*sensor unplugged"):
        fairgrasp.compare(policies={"broken one": broken}, presets=["sector"], episodes=3, out=out,
                          shipped=False)
    assert not out.exists()
    with pytest.raises(ValueError, match="already taken"):
        fairgrasp.compare(policies={"oracle script": lambda obs: np.zeros(7)}, presets=["sector"],
                          episodes=3, out=out, shipped=False)
    assert not out.exists() and not list(tmp_path.iterdir())
    # The thread count follows the CLI's rule (1–256), checked before any policy runs.
    with pytest.raises(ValueError, match="threads = 0: 1–256"):
        fairgrasp.compare(policies={"broken one": broken}, presets=["sector"], episodes=3, out=out,
                          shipped=False, threads=0)
    assert not out.exists()
