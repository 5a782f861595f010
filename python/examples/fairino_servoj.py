"""Stream a fairgrasp export to a real FAIRINO FR3 with FAIRINO's Python SDK (ServoJ).

    fairgrasp export --preset my_cell.toml --episode 3 --out grasp.json
    fairgrasp playback grasp.json                       # it must still grasp in the simulator
    python python/examples/fairino_servoj.py grasp.json  # dry run: checks and prints the plan
    python python/examples/fairino_servoj.py grasp.json --execute --ip 192.168.58.2

What it does with --execute: connects (`Robot.RPC(ip)`), reads the joints, moves to the first
sample with a blocking `MoveJ` at --speed percent, checks that the arm arrived, then
`ServoMoveStart()`, one `ServoJ(joints_deg, axisPos, cmdT=period)` per sample on the stream's
clock (gripper events sent with non-blocking `MoveGripper` at their samples), and `ServoMoveEnd()`
whatever happens (an SDK error, a missed deadline beyond --max-late-ms, Ctrl-C). Without
--execute (the default) it never imports the SDK and never connects.

The SDK is FAIRINO's `fairino` package (github.com/FAIR-INNOVATION/fairino-python-sdk; not on
PyPI); its V2.x `ServoJ(joint_pos, axisPos, acc, vel, cmdT, filterT, gain, ...)` is assumed.
Older SDKs whose `ServoJ` has no `axisPos` are not supported.

SAFETY: read before running on a real arm.
- Nothing here replaces your risk assessment. Keep the emergency stop in reach, the cell clear of
  people, and the pendant's speed override low (e.g. 10 %) for the first runs.
- The stream is only as right as the simulated cell: calibrate the mount first (`fairgrasp
  calibrate points`, then export with that config), and check the start joints this script
  prints against the arm's workspace before the first --execute.
- Run `fairgrasp playback` on the same file first: an export that does not grasp in the simulator
  will not grasp on the arm. Try the stream without the cube, then with it.
- `fairgrasp export` checked the FR3's joint, velocity and acceleration limits and ≤ 1° per sample;
  this script checks the file again and refuses a changed or foreign file the same way, but the
  controller's own limits and collision detection stay your last line.
- The arm must be enabled, in automatic mode, with no error pending (`--enable` calls
  `RobotEnable(1)` and `Mode(0)` for you). The SDK refuses motion while a safety stop is active.
- Gripper commands: `opening_m` of each event is sent as MoveGripper's position in percent of
  the 85 mm stroke (100 = open); check the direction for your gripper (`--gripper-invert`) and
  activate it beforehand (`ActGripper`).
- ServoJ streams from a normal (non real-time) Python process: timing jitter of a few ms happens;
  the run stops at the first deadline missed by more than --max-late-ms.
"""

import argparse
import json
import math
import sys
import time

PERIOD_RANGE = (0.001, 0.016)  # s: what FAIRINO's ROS 2 driver accepts for ServoJ
MAX_STEP_DEG = 1.0  # the driver's guard between consecutive samples
MAX_OPENING_M = 0.085


class StreamError(ValueError):
    """The file cannot be streamed: names the field, sample and joint."""


def load_stream(path):
    """The stream of a `fairgrasp export` JSON: (period_sec, samples [N][6] deg, gripper events)."""
    with open(path) as f:
        doc = json.load(f)
    period = doc.get("period_sec")
    if not isinstance(period, (int, float)) or not PERIOD_RANGE[0] <= period <= PERIOD_RANGE[1]:
        raise StreamError(f"{path}: period_sec = {period!r}: a ServoJ period is 0.001–0.016 s")
    flat = doc.get("joints_deg")
    if not isinstance(flat, list) or not flat or len(flat) % 6:
        raise StreamError(f"{path}: joints_deg must hold 6 numbers per sample")
    samples = [flat[i:i + 6] for i in range(0, len(flat), 6)]
    for n, q in enumerate(samples):
        for j, v in enumerate(q):
            if not isinstance(v, (int, float)) or not math.isfinite(v):
                raise StreamError(f"{path}: sample {n}, j{j + 1}: {v!r} is not a number")
            if n and abs(v - samples[n - 1][j]) > MAX_STEP_DEG + 1e-9:
                raise StreamError(
                    f"{path}: sample {n}, j{j + 1} moves {abs(v - samples[n - 1][j]):.3f}° from the "
                    f"previous sample, more than the {MAX_STEP_DEG}° ServoJ streams allow")
    events = doc.get("gripper", [])
    for k, e in enumerate(events):
        if not 0 <= e.get("sample", -1) < len(samples) or not 0 <= e.get("opening_m", -1) <= MAX_OPENING_M:
            raise StreamError(f"{path}: gripper[{k}] = {e!r} is not a valid event")
    return float(period), samples, events


def _joints_deg(reply):
    """GetActualJointPosDegree's answer across SDK versions: (err, [6]), [err, j1..j6] or err."""
    if isinstance(reply, int):
        return reply, None
    if isinstance(reply, (tuple, list)) and len(reply) == 2 and isinstance(reply[1], (list, tuple)):
        return reply[0], list(reply[1])
    if isinstance(reply, (tuple, list)) and len(reply) == 7:
        return reply[0], list(reply[1:])
    return -1, None


def _check(name, err):
    if err != 0:
        raise RuntimeError(f"{name} returned error {err} (see FAIRINO's SDK error codes)")


def gripper_percent(event, invert):
    percent = 100.0 * event["opening_m"] / MAX_OPENING_M
    return round(100.0 - percent if invert else percent)


def stream(robot, period, samples, events, args, clock=time.perf_counter, sleep=time.sleep):
    """Runs the stream on `robot` (a connected `fairino.Robot.RPC`). Returns the worst lateness [s]."""
    if args.enable:
        _check("RobotEnable", robot.RobotEnable(1))
        _check("Mode", robot.Mode(0))
    err, now = _joints_deg(robot.GetActualJointPosDegree(0))
    _check("GetActualJointPosDegree", err)
    print("arm at   [" + ", ".join(f"{v:.2f}" for v in now) + "] deg")
    _check("MoveJ", robot.MoveJ(samples[0], args.tool, args.user, vel=args.speed))
    err, now = _joints_deg(robot.GetActualJointPosDegree(0))
    _check("GetActualJointPosDegree", err)
    off = max(abs(a - b) for a, b in zip(now, samples[0]))
    if off > args.max_start_deviation:
        raise RuntimeError(f"after MoveJ the arm is {off:.2f}° from the first sample: not streaming")
    by_sample = {e["sample"]: e for e in events} if args.gripper_index else {}
    worst = 0.0
    _check("ServoMoveStart", robot.ServoMoveStart())
    try:
        start = clock()
        for n, q in enumerate(samples):
            if n in by_sample:
                pos = gripper_percent(by_sample[n], args.gripper_invert)
                # index, pos, vel, force [%], maxtime [ms], block (1 = non-blocking), type (0 =
                # parallel), rotNum, rotVel, rotTorque
                _check("MoveGripper", robot.MoveGripper(args.gripper_index, pos, 50, 50, 5000, 1, 0, 0, 0, 0))
            _check("ServoJ", robot.ServoJ(q, [0.0, 0.0, 0.0, 0.0], cmdT=period))
            deadline = start + (n + 1) * period
            late = clock() - deadline
            worst = max(worst, late)
            if late > args.max_late_ms / 1000.0:
                raise RuntimeError(f"sample {n}: {late * 1e3:.1f} ms late (limit {args.max_late_ms} ms)")
            if late < 0:
                sleep(-late)
    finally:
        robot.ServoMoveEnd()
    return worst


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("file", help="a stream JSON from `fairgrasp export` (with its gripper commands, the default)")
    p.add_argument("--execute", action="store_true", help="connect and move the arm (default: dry run)")
    p.add_argument("--ip", default="192.168.58.2", help="the controller's address (FAIRINO's default)")
    p.add_argument("--speed", type=float, default=20.0, help="MoveJ to the start: speed in %% (default 20)")
    p.add_argument("--tool", type=int, default=0, help="tool frame number for MoveJ (0–14)")
    p.add_argument("--user", type=int, default=0, help="workpiece frame number for MoveJ (0–14)")
    p.add_argument("--enable", action="store_true", help="call RobotEnable(1) and Mode(0) (automatic) first")
    p.add_argument("--gripper-index", type=int, default=0,
                   help="send the stream's gripper events to this gripper (1–8; default 0: not sent)")
    p.add_argument("--gripper-invert", action="store_true", help="your gripper's 100 %% is closed")
    p.add_argument("--max-start-deviation", type=float, default=0.5,
                   help="largest joint distance from the first sample after MoveJ [deg]")
    p.add_argument("--max-late-ms", type=float, default=4.0,
                   help="stop when a sample is sent this much later than its time [ms]")
    args = p.parse_args(argv)
    try:
        period, samples, events = load_stream(args.file)
    except (OSError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    print(f"{args.file}: {len(samples)} samples every {period * 1e3:g} ms "
          f"({(len(samples) - 1) * period:.2f} s), {len(events)} gripper events")
    print("start    [" + ", ".join(f"{v:.2f}" for v in samples[0]) + "] deg (MoveJ there first)")
    for e in events:
        state = "sent" if args.gripper_index else "not sent (no --gripper-index)"
        print(f"gripper  sample {e['sample']}: opening {e['opening_m'] * 1e3:.1f} mm "
              f"= {gripper_percent(e, args.gripper_invert)} % ({state})")
    if not args.execute:
        print("dry run: nothing was sent (add --execute to move the arm; read the safety notes first)")
        return 0
    from fairino import Robot  # FAIRINO's SDK, only needed to execute

    robot = Robot.RPC(args.ip)
    try:
        worst = stream(robot, period, samples, events, args)
    except (RuntimeError, KeyboardInterrupt) as e:
        print(f"stopped: {e}", file=sys.stderr)
        return 1
    finally:
        if hasattr(robot, "CloseRPC"):
            robot.CloseRPC()
    print(f"streamed {len(samples)} samples; latest sample {max(worst, 0) * 1e3:.1f} ms late")
    return 0


if __name__ == "__main__":
    sys.exit(main())
