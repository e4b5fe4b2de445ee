"""The ``dhsim`` command: a thin shell over the core.

``fk``, ``check`` and ``list`` never import textual (they are used in
scripts and must start fast); only opening the simulator does. Every bad
input ends as one line on stderr and exit status 2, never a traceback.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections.abc import Sequence

from dhsim_tui import __version__
from dhsim_tui.core.errors import DhsimError
from dhsim_tui.core.library import bundled_names, describe, load_robot
from dhsim_tui.core.model import LENGTH_DECIMALS, MAX_ABS, Robot
from dhsim_tui.core.validation import check_joint_values

EXIT_USAGE = 2
#: options whose value may start with a minus sign (``--q -10,20``)
VALUE_OPTIONS = ("--q", "--xyz", "--oat", "--from")
#: random restarts of `dhsim ik` after the first start fails (seeded: repeatable)
IK_RESTARTS = 30


class UsageError(Exception):
    """A command line argparse could not accept."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str):  # one line, no usage dump
        raise UsageError(f"{self.prog}: error: {message} (see '{self.prog} --help')")


def _glue_negative_values(argv: list[str]) -> list[str]:
    """``--q -10,20`` -> ``--q=-10,20`` (argparse would take -10,20 for an option)."""
    out: list[str] = []
    skip = False
    for i, arg in enumerate(argv):
        if skip:
            skip = False
            continue
        following = argv[i + 1] if i + 1 < len(argv) else ""
        if arg in VALUE_OPTIONS and following[:1] == "-" and following[1:2] in "0123456789.":
            out.append(f"{arg}={argv[i + 1]}")
            skip = True
        else:
            out.append(arg)
    return out


def parse_values(text: str, option: str) -> list[float]:
    """``"0, 30,-45"`` -> numbers, naming the bad item if one isn't a number."""
    items = [item.strip() for item in text.split(",")]
    values = []
    for number, item in enumerate(items, start=1):
        try:
            if "_" in item:  # float() would read 1_0 as 10
                raise ValueError
            value = float(item)
        except ValueError:
            shown = repr(item) if item else "an empty value"
            raise DhsimError(f"{option}: item {number} ({shown}) is not a number") from None
        if not math.isfinite(value) or abs(value) > MAX_ABS:
            raise DhsimError(
                f"{option}: item {number} ({item}) is not a finite number "
                f"of sane size (|value| <= {MAX_ABS:g})"
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


def _row(a: str, b: str, c: str, unit: str = "") -> str:
    return f"{a:>10}{b:>10}{c:>10}   {unit}".rstrip()


def format_fk(robot: Robot, q: Sequence[float]) -> str:
    pose = robot.kinematics.end_effector(q)
    places = LENGTH_DECIMALS[robot.units]
    joints = "  ".join(f"{label} {v:g}" for label, v in zip(robot.labels, q, strict=True))
    return "\n".join(
        [
            robot.name,
            f"q  {joints}",
            _row("X", "Y", "Z", f"({robot.units})"),
            _row(*(f"{_round(v, places):.{places}f}" for v in pose.xyz)),
            _row("O", "A", "T", "(deg)"),
            _row(*(f"{_round(v):.2f}" for v in pose.oat)),
        ]
    )


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
    import numpy as np

    from dhsim_tui.core.ik import solve
    from dhsim_tui.core.orientation import oat_matrix

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
    result = solve(robot, target, start, position_only=args.oat is None, restarts=IK_RESTARTS)
    if not result.success:
        raise DhsimError(f"no solution for {robot.name}: {result.reason}")
    pose = robot.kinematics.end_effector(result.q)
    if args.json:
        print(
            json.dumps(
                {
                    "robot": robot.name,
                    "units": robot.units,
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
        joints = "  ".join(
            f"{label} {_round(v, 4):g}" for label, v in zip(robot.labels, result.q, strict=True)
        )
        print(
            f"{robot.name}\nq  {joints}\nresidual {result.position_error:.2g} {robot.units}, "
            f"{result.orientation_error:.2g} rad"
        )
    return 0


def cmd_check(args: argparse.Namespace) -> int:
    robot, path = load_robot(args.robot)
    print(f"ok  {describe(robot)}  ({path})")
    return 0


def cmd_list(args: argparse.Namespace) -> int:
    status = 0
    for name in bundled_names():
        try:
            robot, _ = load_robot(name)
        except DhsimError as exc:
            print(f"dhsim: error: {exc}", file=sys.stderr)
            status = EXIT_USAGE
            continue
        print(f"{name:<17} {describe(robot)}")
    return status


def cmd_run(args: argparse.Namespace) -> int:
    robot, path = load_robot(args.robot)  # a bad robot is reported before any UI starts
    from dhsim_tui.app import run_app

    return run_app(robot, path, args.renderer)


def cmd_edit(args: argparse.Namespace) -> int:
    robot, path = load_robot(args.robot)
    from dhsim_tui.app import run_app

    return run_app(robot, path, start="edit")


def cmd_new(args: argparse.Namespace) -> int:
    from dhsim_tui.core.editing import new_robot

    robot = new_robot(args.name.strip() or "new robot")  # checked before any UI starts
    from dhsim_tui.app import run_app

    return run_app(robot, None, start="new")


def _subparsers() -> dict[str, _Parser]:
    fk = _Parser(prog="dhsim fk", description="Print the end-effector pose (world XYZ, OAT).")
    fk.add_argument("robot", help="a robot file or a bundled robot's name (see 'dhsim list')")
    fk.add_argument(
        "--q",
        metavar="V1,V2,...",
        help="joint values (deg or the robot's length unit); default: home",
    )
    fk.add_argument("--pose", metavar="NAME", help="a named pose of the robot")
    fk.add_argument("--json", action="store_true", help="print one JSON object")
    fk.set_defaults(func=cmd_fk)
    check = _Parser(prog="dhsim check", description="Validate a robot and summarise it.")
    check.add_argument("robot", help="a robot file or a bundled robot's name")
    check.set_defaults(func=cmd_check)
    listing = _Parser(prog="dhsim list", description="List the bundled robots.")
    listing.set_defaults(func=cmd_list)
    ik = _Parser(
        prog="dhsim ik", description="Joint values that reach a pose (inverse kinematics)."
    )
    ik.add_argument("robot", help="a robot file or a bundled robot's name")
    ik.add_argument("--xyz", required=True, metavar="X,Y,Z", help="target position (robot unit)")
    ik.add_argument("--oat", metavar="O,A,T", help="target orientation (deg); default: any")
    ik.add_argument(
        "--from", dest="start", metavar="V1,V2,...", help="starting joint values; default: home"
    )
    ik.add_argument("--json", action="store_true", help="print one JSON object")
    ik.set_defaults(func=cmd_ik)
    edit = _Parser(prog="dhsim edit", description="Open a robot in the table editor.")
    edit.add_argument("robot", help="a robot file or a bundled robot's name")
    edit.set_defaults(func=cmd_edit)
    new = _Parser(prog="dhsim new", description="Start a new robot in the table editor.")
    new.add_argument("name", nargs="?", default="new robot", help="the robot's name")
    new.set_defaults(func=cmd_new)
    return {"fk": fk, "ik": ik, "check": check, "list": listing, "edit": edit, "new": new}


MAIN_HELP = """\
usage: dhsim [ROBOT] [--renderer braille|plotext]
                                 open the simulator (default: the bundled Puma 560)
       dhsim fk ROBOT [--q V1,V2,...] [--pose NAME] [--json]
       dhsim ik ROBOT --xyz X,Y,Z [--oat O,A,T] [--from V1,V2,...] [--json]
       dhsim check ROBOT
       dhsim list
       dhsim edit ROBOT            the table editor
       dhsim new [NAME]            a new robot in the table editor

ROBOT is a robot file (.toml) or a bundled robot's name, e.g. puma560.
Run 'dhsim COMMAND --help' for a command's options."""


def _main_parser() -> _Parser:
    parser = _Parser(prog="dhsim", add_help=False)
    parser.add_argument("robot", nargs="?", default=None)
    parser.add_argument("--renderer", choices=("braille", "plotext"), default="braille")
    parser.set_defaults(func=cmd_run)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    args_list = list(sys.argv[1:] if argv is None else argv)
    try:
        if args_list and args_list[0] in ("-h", "--help"):
            print(MAIN_HELP)
            return 0
        if args_list and args_list[0] == "--version":
            print(f"dhsim {__version__}")
            return 0
        subs = _subparsers()
        if args_list and args_list[0] in subs:
            parser = subs[args_list[0]]
            args = parser.parse_args(_glue_negative_values(args_list[1:]))
        else:
            args = _main_parser().parse_args(args_list)
        return args.func(args)
    except UsageError as exc:
        print(exc, file=sys.stderr)
        return EXIT_USAGE
    except DhsimError as exc:
        print(f"dhsim: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:  # e.g. `dhsim list | head -1`
        sys.stderr.close()
        return 0
