"""The ``dhsim`` command: a thin shell over the core.

``fk``, ``ik``, ``check`` and ``list`` never import textual (they are used in
scripts and must start fast); only opening the simulator does, and only when
stdin and stdout are a terminal. Every bad input ends as one line on stderr
and exit status 2, never a traceback; an unexpected error as one line and
exit status 1. Whatever the line quotes from the user or a file is passed
through :func:`printable`, so no control character reaches the terminal.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import sys
from collections.abc import Sequence

import numpy as np

from dhsim_tui import __version__
from dhsim_tui.cli_files import subparsers as files_subparsers
from dhsim_tui.cli_workspace import subparsers as workspace_subparsers
from dhsim_tui.core.errors import DhsimError
from dhsim_tui.core.ik import solve
from dhsim_tui.core.ik_all import all_solutions
from dhsim_tui.core.ik_reasons import angle, length
from dhsim_tui.core.library import DEFAULT_ROBOT, bundled_names, describe, load_robot, resolve
from dhsim_tui.core.model import LENGTH_DECIMALS, MAX_ABS, Robot
from dhsim_tui.core.orientation import oat_matrix
from dhsim_tui.core.robotfile import load_with_stamp
from dhsim_tui.core.text import printable
from dhsim_tui.core.validation import check_joint_values, fmt
from dhsim_tui.terminal import original_environ, wants_ascii

EXIT_USAGE = 2
EXIT_INTERNAL = 1
EXIT_INTERRUPTED = 130
NEEDS_TERMINAL = (
    "dhsim: the simulator needs an interactive terminal (over SSH use ssh -t); "
    "fk, ik, check, list, import, export, convert and workspace work without one"
)
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
            shown = printable(repr(item)) if item else "an empty value"
            raise DhsimError(f"{option}: item {number} ({shown}) is not a number") from None
        if not math.isfinite(value) or abs(value) > MAX_ABS:
            raise DhsimError(
                f"{option}: item {number} ({printable(item)}) is not a finite number "
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
    return "\n".join([printable(robot.name), _joints_line(robot, q), *table])


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
    result = solve(robot, target, start, position_only=args.oat is None, restarts=IK_RESTARTS)
    if not result.success:
        raise DhsimError(f"no solution for {robot.name}: {result.reason}")
    if not all(math.isfinite(v) for v in (*result.q, result.residual)):
        raise DhsimError(f"no solution for {robot.name}: the solver lost precision")
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
        q = [_round(v, 4) for v in result.q]
        print(
            f"{printable(robot.name)}\n{_joints_line(robot, q)}\n"
            f"residual {length(robot, result.position_error)}, "
            f"{angle(result.orientation_error)}"
        )
    return 0


def _ik_all(robot: Robot, target, start, *, position_only: bool, as_json: bool) -> int:
    """``dhsim ik --all``: every solution, nearest to the start first."""
    found = all_solutions(robot, target, start, position_only=position_only)
    if not found.solutions:
        raise DhsimError(f"no solution for {robot.name}: {found.note}")
    if as_json:
        solutions = [
            {"q": list(s.q), "config": s.config, "residual": s.residual} for s in found.solutions
        ]
        print(
            json.dumps(
                {
                    "robot": robot.name,
                    "units": robot.units,
                    "method": found.method,
                    "family": found.family,
                    "solutions": solutions,
                }
            )
        )
        return 0
    count = len(found.solutions)
    kind = "representatives of a continuous family" if found.family else "solutions"
    lines = [printable(robot.name), f"{count} {kind} ({found.method})"]
    if found.note:
        lines.append(printable(found.note))
    for s in found.solutions:
        q = [_round(v, 4) for v in s.q]
        words = f"  {s.config}" if s.config else ""
        lines.append(f"{_joints_line(robot, q)}{words}  residual {length(robot, s.residual)}")
    print("\n".join(lines))
    return 0


def cmd_check(args: argparse.Namespace) -> int:
    robot, path = load_robot(args.robot)
    print(printable(f"ok  {describe(robot)}  ({path})"))
    return 0


def cmd_list(args: argparse.Namespace) -> int:
    status = 0
    for name in bundled_names():
        try:
            robot, _ = load_robot(name)
        except DhsimError as exc:
            print(f"dhsim: error: {printable(str(exc))}", file=sys.stderr)
            status = EXIT_USAGE
            continue
        print(printable(f"{name:<17} {describe(robot)}"))
    return status


def has_terminal() -> bool:
    """Both stdin and stdout are a terminal (the simulator reads keys and draws)."""
    for stream in (sys.stdin, sys.stdout):
        try:
            if stream is None or not os.isatty(stream.fileno()):
                return False
        except (AttributeError, OSError, ValueError):  # closed, or not a real file
            return False
    return True


def _open(argument: str | None):
    """The robot, its file and the stamp of the very bytes read (a save later
    refuses to overwrite a change made on disk since then)."""
    path = resolve(argument if argument is not None else DEFAULT_ROBOT)
    robot, stamp = load_with_stamp(path)
    return robot, path, stamp


def ascii_screen(args: argparse.Namespace) -> bool:
    """Whether the simulator draws in 7-bit ASCII: ``--ascii`` or ``--unicode``
    if given, else the locale the process was started with and TERM.
    In ASCII mode whatever is printed after the app ends is ASCII as well
    (backslash escapes for what has no ASCII form)."""
    ascii = wants_ascii(original_environ(), force=args.force_ascii)
    if ascii:
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(AttributeError, ValueError, OSError):
                stream.flush()
                stream.reconfigure(encoding="ascii", errors="backslashreplace")  # type: ignore[union-attr]
    return ascii


def cmd_run(args: argparse.Namespace) -> int:
    robot, path, stamp = _open(args.robot)  # a bad robot is reported before any UI starts
    from dhsim_tui.app import run_app  # textual loads only for the simulator

    return run_app(
        robot, path, args.renderer, stamp=stamp, ascii=ascii_screen(args), theme=args.theme
    )


def cmd_edit(args: argparse.Namespace) -> int:
    robot, path, stamp = _open(args.robot)
    from dhsim_tui.app import run_app

    return run_app(
        robot, path, start="edit", stamp=stamp, ascii=ascii_screen(args), theme=args.theme
    )


def cmd_new(args: argparse.Namespace) -> int:
    from dhsim_tui.core.editing import new_robot

    robot = new_robot(args.name.strip() or "new robot")  # checked before any UI starts
    from dhsim_tui.app import run_app

    return run_app(robot, None, start="new", ascii=ascii_screen(args), theme=args.theme)


def _add_charset_options(parser: argparse.ArgumentParser) -> None:
    """``--ascii`` / ``--unicode``: override what the locale and TERM say;
    ``--theme``: the colours."""
    parser.add_argument(
        "--theme",
        choices=("dark", "light", "ansi"),
        default="dark",
        help="colours: dark (default), light, or ansi (the terminal's own palette)",
    )
    group = parser.add_mutually_exclusive_group()
    group.add_argument(
        "--ascii",
        dest="force_ascii",
        action="store_const",
        const=True,
        default=None,
        help="draw only 7-bit ASCII (default when the locale is not UTF-8, or TERM=linux)",
    )
    group.add_argument(
        "--unicode",
        dest="force_ascii",
        action="store_const",
        const=False,
        help="draw with Unicode box drawing and symbols whatever the locale says",
    )


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
    ik.add_argument(
        "--all", action="store_true", help="every solution within limits, nearest first"
    )
    ik.add_argument("--json", action="store_true", help="print one JSON object")
    ik.set_defaults(func=cmd_ik)
    edit = _Parser(prog="dhsim edit", description="Open a robot in the table editor.")
    edit.add_argument("robot", help="a robot file or a bundled robot's name")
    _add_charset_options(edit)
    edit.set_defaults(func=cmd_edit)
    new = _Parser(prog="dhsim new", description="Start a new robot in the table editor.")
    new.add_argument("name", nargs="?", default="new robot", help="the robot's name")
    _add_charset_options(new)
    new.set_defaults(func=cmd_new)
    return {
        "fk": fk,
        "ik": ik,
        "check": check,
        "list": listing,
        "edit": edit,
        "new": new,
        **files_subparsers(_Parser),
        **workspace_subparsers(_Parser),
    }


MAIN_HELP = """\
usage: dhsim [ROBOT] [--renderer plotext|braille] [--ascii | --unicode]
             [--theme dark|light|ansi]
                                 open the simulator (default: the bundled Puma 560)
       dhsim fk ROBOT [--q V1,V2,...] [--pose NAME] [--json]
       dhsim ik ROBOT --xyz X,Y,Z [--oat O,A,T] [--from V1,V2,...] [--all] [--json]
       dhsim check ROBOT
       dhsim list
       dhsim import FILE.urdf|FILE.csv [--tip LINK] [--base LINK]
                    [--convention standard|modified] [--units mm|cm|m|in] [-o OUT.toml]
       dhsim export ROBOT --format urdf|csv|json [-o FILE]
       dhsim convert ROBOT --convention standard|modified [-o FILE.toml]
       dhsim workspace ROBOT [--n N] [--seed S] [--json]
                                 where the tool can go: bounding box and reach
       dhsim edit ROBOT [--ascii | --unicode]
                                 the table editor
       dhsim new [NAME] [--ascii | --unicode]
                                 a new robot in the table editor

ROBOT is a robot file (.toml) or a bundled robot's name, e.g. puma560.
The simulator draws in 7-bit ASCII when the locale (LC_ALL, LC_CTYPE, LANG)
is not UTF-8 or TERM=linux; --ascii and --unicode decide instead.
--theme ansi uses the terminal's own colour palette.
Run 'dhsim COMMAND --help' for a command's options."""


def _main_parser() -> _Parser:
    parser = _Parser(prog="dhsim", add_help=False)
    parser.add_argument("robot", nargs="?", default=None)
    parser.add_argument("--renderer", choices=("plotext", "braille"), default="plotext")
    _add_charset_options(parser)
    parser.set_defaults(func=cmd_run)
    return parser


#: the commands that open the simulator: they need a terminal
INTERACTIVE = (cmd_run, cmd_edit, cmd_new)


def main(argv: Sequence[str] | None = None) -> int:
    args_list = list(sys.argv[1:] if argv is None else argv)
    _escape_unencodable(sys.stdout)
    _escape_unencodable(sys.stderr)
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
        if args.func in INTERACTIVE and not has_terminal():
            print(NEEDS_TERMINAL, file=sys.stderr)
            return EXIT_USAGE
        with np.errstate(all="ignore"):  # a result that lost precision is checked, not warned
            status = args.func(args)
        sys.stdout.flush()  # a closed pipe shows here, not in Python's exit handler
        return status
    except UsageError as exc:
        print(printable(str(exc)), file=sys.stderr)
        return EXIT_USAGE
    except DhsimError as exc:
        print(f"dhsim: error: {printable(str(exc))}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        return EXIT_INTERRUPTED
    except BrokenPipeError:  # e.g. `dhsim list | head -1`
        _silence_stdout()
        return 0
    except Exception as exc:  # the last resort: one line and a failure status
        print(
            f"dhsim: internal error: {printable(f'{type(exc).__name__}: {exc}')}",
            file=sys.stderr,
        )
        return EXIT_INTERNAL


def _escape_unencodable(stream: object) -> None:
    """Text the terminal's encoding cannot show (a C locale and a name in
    Chinese) is written as backslash escapes instead of raising an error."""
    with contextlib.suppress(AttributeError, ValueError, OSError):
        stream.reconfigure(errors="backslashreplace")  # type: ignore[attr-defined]


def _silence_stdout() -> None:
    """After a closed pipe, send what Python still flushes at exit nowhere."""
    with contextlib.suppress(AttributeError, ValueError, OSError):
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
