"""python/examples/fairino_servoj.py against a stub of FAIRINO's SDK that records every call: the
dry run never connects, --execute sends MoveJ to the start then one ServoJ per sample in order
with the stream's period, gripper events at their samples, and always ends the servo mode; a
file that breaks the 1° guard is refused before connecting."""

import importlib.util
import json
import math
import sys
import types
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "fairino_servoj.py"


def load_example():
    spec = importlib.util.spec_from_file_location("fairino_servoj", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class StubRobot:
    """Records calls like FAIRINO's `Robot.RPC`; the arm is wherever MoveJ or ServoJ put it."""

    instances = []

    def __init__(self, ip, fail_servoj_at=None):
        self.ip, self.calls, self.q = ip, [], [0.0] * 6
        self.fail_servoj_at = fail_servoj_at
        StubRobot.instances.append(self)

    def GetActualJointPosDegree(self, flag=1):
        self.calls.append(("GetActualJointPosDegree", flag))
        return 0, list(self.q)

    def MoveJ(self, joint_pos, tool, user, desc_pos=None, vel=20.0, **_):
        self.calls.append(("MoveJ", list(joint_pos), tool, user, vel))
        self.q = list(joint_pos)
        return 0

    def ServoMoveStart(self):
        self.calls.append(("ServoMoveStart",))
        return 0

    def ServoJ(self, joint_pos, axisPos, acc=0.0, vel=0.0, cmdT=0.008, filterT=0.0, gain=0.0):
        n = sum(1 for c in self.calls if c[0] == "ServoJ")
        self.calls.append(("ServoJ", list(joint_pos), cmdT))
        self.q = list(joint_pos)
        return 14 if n == self.fail_servoj_at else 0

    def MoveGripper(self, index, pos, vel, force, maxtime, block, type, rotNum, rotVel, rotTorque):
        self.calls.append(("MoveGripper", index, pos, block))
        return 0

    def ServoMoveEnd(self):
        self.calls.append(("ServoMoveEnd",))
        return 0

    def CloseRPC(self):
        self.calls.append(("CloseRPC",))


@pytest.fixture
def sdk(monkeypatch):
    """A `fairino` module whose Robot.RPC builds a StubRobot (options via sdk.options)."""
    StubRobot.instances = []
    options = {}
    fairino = types.ModuleType("fairino")
    fairino.Robot = types.SimpleNamespace(RPC=lambda ip: StubRobot(ip, **options))
    monkeypatch.setitem(sys.modules, "fairino", fairino)
    return types.SimpleNamespace(options=options, robots=StubRobot.instances)


def write_stream(path, n=60, period=0.004, jump_at=None):
    """A smooth stream of n samples on j1 and j2 with an open and a close event."""
    flat = []
    for k in range(n):
        s = 0.5 * (1 - math.cos(math.pi * k / (n - 1)))
        q = [10.0 + 8.0 * s, -80.0 - 5.0 * s, -80.0, -108.0, 90.0, 0.0]
        if jump_at is not None and k >= jump_at:
            q[2] += 2.0
        flat += q
    events = [{"sample": 0, "command": -1.0, "opening_m": 0.085},
              {"sample": n // 2, "command": 1.0, "opening_m": 0.0}]
    path.write_text(json.dumps({"period_sec": period, "joints_deg": flat, "gripper": events}))
    return [flat[i:i + 6] for i in range(0, len(flat), 6)]


def test_the_dry_run_checks_and_prints_without_connecting(tmp_path, sdk, capsys):
    write_stream(tmp_path / "s.json")
    assert load_example().main([str(tmp_path / "s.json")]) == 0
    assert sdk.robots == []
    assert "dry run: nothing was sent" in capsys.readouterr().out


def test_execute_moves_to_the_start_then_streams_every_sample_in_order(tmp_path, sdk):
    samples = write_stream(tmp_path / "s.json")
    code = load_example().main([str(tmp_path / "s.json"), "--execute", "--ip", "10.0.0.7",
                                "--gripper-index", "1", "--max-late-ms", "1000"])
    assert code == 0
    (robot,) = sdk.robots
    names = [c[0] for c in robot.calls]
    assert robot.ip == "10.0.0.7"
    assert names[:4] == ["GetActualJointPosDegree", "MoveJ", "GetActualJointPosDegree", "ServoMoveStart"]
    assert robot.calls[1] == ("MoveJ", samples[0], 0, 0, 20.0)
    servo = [c for c in robot.calls if c[0] == "ServoJ"]
    assert [c[1] for c in servo] == samples and all(c[2] == 0.004 for c in servo)
    grips = [(i, c) for i, c in enumerate(robot.calls) if c[0] == "MoveGripper"]
    assert [c[2] for _, c in grips] == [100, 0] and all(c[3] == 1 for _, c in grips)
    # The close is sent just before the sample it belongs to.
    close_at = grips[1][0]
    assert robot.calls[close_at + 1] == ("ServoJ", samples[30], 0.004)
    assert names[-2:] == ["ServoMoveEnd", "CloseRPC"]


def test_an_sdk_error_mid_stream_still_ends_the_servo_mode(tmp_path, sdk, capsys):
    write_stream(tmp_path / "s.json")
    sdk.options["fail_servoj_at"] = 10
    code = load_example().main([str(tmp_path / "s.json"), "--execute", "--max-late-ms", "1000"])
    assert code == 1
    (robot,) = sdk.robots
    assert sum(1 for c in robot.calls if c[0] == "ServoJ") == 11
    assert [c[0] for c in robot.calls][-2:] == ["ServoMoveEnd", "CloseRPC"]
    assert "ServoJ returned error 14" in capsys.readouterr().err


def test_a_file_breaking_the_one_degree_guard_is_refused_before_connecting(tmp_path, sdk, capsys):
    write_stream(tmp_path / "s.json", jump_at=25)
    assert load_example().main([str(tmp_path / "s.json"), "--execute"]) == 2
    assert sdk.robots == []
    assert "sample 25, j3 moves 2.000°" in capsys.readouterr().err


def test_a_fairgrasp_export_streams_sample_for_sample(tmp_path, sdk, cli):
    out = tmp_path / "grasp.json"
    report = cli("export", "--gripper", "--period", "0.004", "--out", str(out), "--json")
    doc = json.loads(out.read_text())
    assert load_example().main([str(out), "--execute", "--gripper-index", "1", "--max-late-ms", "1000"]) == 0
    servo = [c for c in sdk.robots[0].calls if c[0] == "ServoJ"]
    assert len(servo) == report["samples"] == len(doc["joints_deg"]) // 6
    assert servo[-1][1] == doc["joints_deg"][-6:]
