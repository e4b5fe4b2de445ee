"""``dhsim fk`` and ``dhsim ik``: poses from joint values and back.

A thin shell over :mod:`dhsim_tui.core.model.kinematics`, :mod:`dhsim_tui.core.ik.numerical`
and :mod:`dhsim_tui.core.ik.solutions` (``ik --all``). Neither imports textual:
both start fast in scripts.

``dhsim ik`` without a solution is an answer, not a usage error: exit
status :data:`EXIT_NO_SOLUTION` (3, as ``dhsim run`` when its check finds
problems) and one line on stderr saying why, or with ``--json`` one object
on stdout (``"solved": false`` and the ``"reason"``). 2 stays for bad input.
"""

from __future__ import annotations

import argparse
import json
import math
from collections.abc import Sequence

import numpy as np

from dhsim_tui.cli.streams import to_stderr
from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.ik.nearest import inverse
from dhsim_tui.core.ik.reasons import angle, length
from dhsim_tui.core.ik.solutions import all_solutions
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.orientation import oat_matrix
from dhsim_tui.core.model.robot import LENGTH_DECIMALS, MAX_ABS, Robot
from dhsim_tui.core.model.text import counted, printable, shortened
from dhsim_tui.core.model.validation import check_joint_values, fmt

#: options whose value may start with a minus sign (``--q -10,20``)
VALUE_OPTIONS = ("--q", "--xyz", "--oat", "--from", "--orbit")
#: random restarts of `dhsim ik` after the first start fails (seeded: repeatable)
IK_RESTARTS = 30
#: the exit status of `dhsim ik` when no joint values reach the pose (as `dhsim run`
#: exits when its path check finds problems); 2 stays for bad input
EXIT_NO_SOLUTION = 3


def no_solution(robot: Robot, reason: str, as_json: bool, **fields) -> int:
    """Say why there is no solution (a line on stderr, or with ``--json`` an
    object on stdout); the exit status :data:`EXIT_NO_SOLUTION`."""
    if as_json:
        answer = {"robot": robot.name, "units": robot.units, "solved": False, "reason": reason}
        print(json.dumps({**answer, **fields}))
    else:
        to_stderr(printable(f"dhsim: no solution for {shortened(robot.name)}: {reason}"))
    return EXIT_NO_SOLUTION


def parse_values(text: str, option: str) -> list[float]:
    """``"0, 30,-45"`` -> numbers, naming the bad item if one isn't a number.
    Digits are ASCII only: float() would also read ``١`` (Arabic-Indic) as 1."""
    items = [item.strip() for item in text.split(",")]
    values = []
    for number, item in enumerate(items, start=1):
        try:
            if "_" in item or not item.isascii():  # float() would read 1_0 as 10
                raise ValueError
            value = float(item)
        except ValueError:
            shown = printable(repr(shortened(item))) if item else "an empty value"
            digits = "; a number is written in ASCII (0-9 . - + e)" if not item.isascii() else ""
            raise DhsimError(f"{option}: item {number} ({shown}) is not a number{digits}") from None
        if not math.isfinite(value) or abs(value) > MAX_ABS:
            raise DhsimError(
                f"{option}: item {number} ({printable(shortened(item))}) is not a finite number "
                f"of sane size (|value| <= {fmt(MAX_ABS)})"
            )
        values.append(value)
    return values


def joint_values(robot: Robot, q_text: str | None, pose: str | None) -> tuple[float, ...]:
    if q_text is not None and pose is not None:
        raise DhsimError("give either --q or --pose, not both")
    if pose is not None:
        return robot.pose(pose)
    if q_text is None:
        return robot.home
    return check_joint_values(robot, parse_values(q_text, "--q"), "--q")


def _round(value: float, places: int = 2) -> float:
    return round(value, places) + 0.0  # + 0.0 turns -0.0 into 0.0


def _table(rows: list[tuple[str, str, str, str]]) -> list[str]:
    """Right-aligned columns 10 wide, wider when a number needs it (a column of
    a huge robot), so neighbouring numbers never run together."""
    width = max(10, *(len(cell) + 2 for row in rows for cell in row[:3]))
    return [f"{a:>{width}}{b:>{width}}{c:>{width}}   {unit}".rstrip() for a, b, c, unit in rows]


def _joints_line(robot: Robot, q: Sequence[float]) -> str:
    return "q  " + "  ".join(f"{label} {fmt(v)}" for label, v in zip(robot.labels, q, strict=True))


def format_fk(robot: Robot, q: Sequence[float]) -> str:
    pose = robot.kinematics.end_effector(q)
    places = LENGTH_DECIMALS[robot.units]
    xyz = [f"{_round(v, places):.{places}f}" for v in pose.xyz]
    oat = [f"{_round(v):.2f}" for v in pose.oat]
    table = _table(
        [("X", "Y", "Z", f"({robot.units})"), (*xyz, ""), ("O", "A", "T", "(deg)"), (*oat, "")]
    )
    return "\n".join([printable(shortened(robot.name)), _joints_line(robot, q), *table])


def fk_json(robot: Robot, q: Sequence[float]) -> str:
    pose = robot.kinematics.end_effector(q)
    return json.dumps(
        {
            "robot": robot.name,
            "units": robot.units,
            "q": list(q),
            "xyz": list(pose.xyz),
            "oat": list(pose.oat),
            "rpy": list(pose.rpy),
            "T": pose.matrix.tolist(),
        }
    )


def cmd_fk(args: argparse.Namespace) -> int:
    robot, _ = load_robot(args.robot)
    q = joint_values(robot, args.q, args.pose)
    print(fk_json(robot, q) if args.json else format_fk(robot, q))
    return 0


def cmd_ik(args: argparse.Namespace) -> int:
    robot, _ = load_robot(args.robot)
    xyz = parse_values(args.xyz, "--xyz")
    if len(xyz) != 3:
        raise DhsimError(f"--xyz: expected 3 numbers X,Y,Z, got {len(xyz)}")
    target = np.eye(4)
    target[:3, 3] = xyz
    if args.oat is not None:
        oat = parse_values(args.oat, "--oat")
        if len(oat) != 3:
            raise DhsimError(f"--oat: expected 3 angles O,A,T, got {len(oat)}")
        target[:3, :3] = oat_matrix(*oat)
    start = robot.home
    if args.start is not None:
        start = check_joint_values(robot, parse_values(args.start, "--from"), "--from")
    if args.all:
        return _ik_all(robot, target, start, position_only=args.oat is None, as_json=args.json)
    result = inverse(robot, target, start, position_only=args.oat is None, restarts=IK_RESTARTS)
    if not result.success:
        return no_solution(robot, result.reason, args.json)
    if not all(math.isfinite(v) for v in (*result.q, result.residual)):
        return no_solution(robot, "the solver lost precision", args.json)
    pose = robot.kinematics.end_effector(result.q)
    if args.json:
        print(
            json.dumps(
                {
                    "robot": robot.name,
                    "units": robot.units,
                    "solved": True,
                    "q": list(result.q),
                    "xyz": list(pose.xyz),
                    "oat": list(pose.oat),
                    "residual": result.residual,
                    "position_error": result.position_error,
                    "orientation_error": result.orientation_error,
                }
            )
        )
    else:
        q = [_round(v, 4) for v in result.q]
        print(
            f"{printable(shortened(robot.name))}\n{_joints_line(robot, q)}\n"
            f"residual {length(robot, result.position_error)}, "
            f"{angle(result.orientation_error)}"
        )
    return 0


def _ik_all(robot: Robot, target, start, *, position_only: bool, as_json: bool) -> int:
    """``dhsim ik --all``: every solution, nearest to the start first."""
    found = all_solutions(robot, target, start, position_only=position_only)
    if not found.solutions:
        extra = {"method": found.method, "family": found.family, "solutions": []}
        return no_solution(robot, found.note, as_json, **extra)
    if as_json:
        solutions = [
            {"q": list(s.q), "config": s.config, "residual": s.residual} for s in found.solutions
        ]
        print(
            json.dumps(
                {
                    "robot": robot.name,
                    "units": robot.units,
                    "solved": True,
                    "method": found.method,
                    "family": found.family,
                    "solutions": solutions,
                }
            )
        )
        return 0
    count = len(found.solutions)
    if found.family:
        kind = counted(count, "representative", "representatives") + " of a continuous family"
    else:
        kind = counted(count, "solution")
    lines = [printable(shortened(robot.name)), f"{kind} ({found.method})"]
    if found.note:
        lines.append(printable(found.note))
    for s in found.solutions:
        q = [_round(v, 4) for v in s.q]
        words = f"  {s.config}" if s.config else ""
        lines.append(f"{_joints_line(robot, q)}{words}  residual {length(robot, s.residual)}")
    print("\n".join(lines))
    return 0


def subparsers(parser_class: type[argparse.ArgumentParser]) -> dict[str, argparse.ArgumentParser]:
    """The two commands' parsers (``parser_class`` reports errors in one line)."""
    _Parser = parser_class
    fk = parser_class(prog="dhsim fk", description="Print the end-effector pose (world XYZ, OAT).")
    fk.add_argument("robot", help="a robot file or a bundled robot's name (see 'dhsim list')")
    fk.add_argument(
        "--q",
        metavar="V1,V2,...",
        help="joint values (deg or the robot's length unit); default: home",
    )
    fk.add_argument("--pose", metavar="NAME", help="a named pose of the robot")
    fk.add_argument("--json", action="store_true", help="print one JSON object")
    fk.set_defaults(func=cmd_fk)
    ik = parser_class(
        prog="dhsim ik",
        description="Joint values that reach a pose (inverse kinematics). Exit status 0: "
        "solved; 3: no solution (--json: an object saying why); 2: bad input.",
    )
    ik.add_argument("robot", help="a robot file or a bundled robot's name")
    ik.add_argument("--xyz", required=True, metavar="X,Y,Z", help="target position (robot unit)")
    ik.add_argument("--oat", metavar="O,A,T", help="target orientation (deg); default: any")
    ik.add_argument(
        "--from", dest="start", metavar="V1,V2,...", help="starting joint values; default: home"
    )
    ik.add_argument(
        "--all", action="store_true", help="every solution within limits, nearest first"
    )
    ik.add_argument("--json", action="store_true", help="print one JSON object")
    ik.set_defaults(func=cmd_ik)
    return {"fk": fk, "ik": ik}
