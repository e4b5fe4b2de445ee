"""``dhsim run ROBOT PROGRAM``: play a program as a controller would and
check its path before it runs on the arm.

A thin shell over :mod:`dhsim_tui.core.motion.trajectory` (the samples),
:mod:`dhsim_tui.core.motion.path_check` (the problems) and
:mod:`dhsim_tui.core.motion.trajectory_csv` (``--csv``). It prints the
duration, each step's start time and length, and every problem with its
step, time and joint or frame. ``--json`` prints the same facts as one
object (the samples themselves are the CSV's, not the JSON's); ``--plot``
draws the joints and the tool's speed against time (plotext).

Exit status: 0 when the path is clean, :data:`EXIT_PROBLEMS` (3) when the
check found problems, 2 for bad input (one line on stderr).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import sys
from pathlib import Path

from dhsim_tui.cli.kinematics import parse_values
from dhsim_tui.cli.streams import to_stderr
from dhsim_tui.core.files.atomicfile import write_file
from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import counted, printable, shortened
from dhsim_tui.core.model.validation import check_joint_values
from dhsim_tui.core.motion.path_check import check_path
from dhsim_tui.core.motion.trajectory import DEFAULT_RATE, MAX_RATE, MIN_RATE, sample
from dhsim_tui.terminal.locale_env import original_environ, wants_ascii

#: the exit status when the path check found problems
EXIT_PROBLEMS = 3
#: ``dhsim run --help``'s last words: the CSV's columns and their units
CSV_EPILOG = """\
--csv writes the header row first, then one row per sample:
  time          s, from the program's start
  step          the step, 1-based (0: a program without steps)
  move          joint, linear or wait
  q1 ... qN     the joints: deg (revolute), the robot's unit (prismatic)
  x, y, z       the tool point in the world, the robot's unit (as dhsim fk)
  o, a, t       the tool's orientation, deg (as dhsim fk)
  mu            the manipulability, dimensionless (below 0.001: singular)
--json gives each column's unit for the robot as "column_units"."""


def rate_value(text: str) -> float:
    """``--rate``: samples a second, a number from MIN_RATE to MAX_RATE."""
    try:
        if "_" in text or not text.isascii():
            raise ValueError
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{shortened(text)!r} is not a number (ASCII digits 0-9)"
        ) from None
    if not math.isfinite(value) or not MIN_RATE <= value <= MAX_RATE:
        raise argparse.ArgumentTypeError(
            f"{shortened(text)!r}: give {MIN_RATE:g} to {MAX_RATE:g} samples a second"
        )
    return value


def start_joints(robot: Robot, text: str | None) -> tuple[float, ...]:
    """``--from``: a pose name of the robot or joint values; default: home."""
    if text is None:
        return robot.home
    if text in robot.pose_names:
        return robot.pose(text)
    return check_joint_values(robot, parse_values(text, "--from"), "--from")


def _seconds(value: float) -> str:
    return f"{round(value, 3) + 0.0:.3f} s"


def format_run(trajectory, problems) -> str:
    """The text report: a summary line, the steps, the problems."""
    robot, program = trajectory.robot, trajectory.program
    head = (
        f"{printable(shortened(robot.name))}: program {printable(shortened(program.name))!r}, "
        f"{counted(len(program.steps), 'step')}, {_seconds(trajectory.duration)} "
        f"at {trajectory.rate:g} Hz ({counted(len(trajectory.time), 'sample')})"
    )
    lines = [head]
    if trajectory.spans:
        width = max(len(_seconds(span.end)) for span in trajectory.spans)
        lines.append(f"{'step':>4}  {'start':>{width}}  {'length':>{width}}  move")
        for span in trajectory.spans:
            lines.append(
                f"{span.number:>4}  {_seconds(span.start):>{width}}  "
                f"{_seconds(span.duration):>{width}}  {printable(shortened(span.step.describe()))}"
            )
    if not problems:
        lines.append("the path is clean: no problems found")
        return "\n".join(lines)
    lines.append(f"{counted(len(problems), 'problem')}:")
    for problem in problems:
        when = _seconds(problem.time)
        if problem.until > problem.time:
            when = f"{_seconds(problem.time)[:-2]} to {_seconds(problem.until)}"
        lines.append(f"  step {problem.step}, {when}, {problem.kind}: {printable(problem.detail)}")
    return "\n".join(lines)


def run_json(trajectory, problems) -> str:
    """One JSON object: the run, its steps and its problems (not the samples)."""
    # the CSV module (and csv) load only when a command needs them, not at start-up
    from dhsim_tui.core.motion.trajectory_csv import column_units

    robot = trajectory.robot
    xyz = robot.kinematics
    steps = [
        {
            "step": span.number,
            "move": span.move,
            "text": span.step.describe(),
            "start": span.start,
            "length": span.duration,
            "q_end": list(span.q_end),
            "xyz_end": list(xyz.position(span.q_end)),
        }
        for span in trajectory.spans
    ]
    return json.dumps(
        {
            "robot": robot.name,
            "units": robot.units,
            "program": trajectory.program.name,
            "rate": trajectory.rate,
            "start": trajectory.q[0].tolist(),
            "duration": trajectory.duration,
            "samples": len(trajectory.time),
            "column_units": column_units(robot),
            "steps": steps,
            "clean": not problems,
            "problems": [problem.as_dict() for problem in problems],
        }
    )


def _check_csv_target(args: argparse.Namespace) -> None:
    """Before any work: a name, and an existing file only with --force."""
    out = args.csv
    if out is None or out == "-":
        if out == "-" and (args.json or args.plot):
            raise DhsimError("--csv -: the CSV on stdout can't share it with --json or --plot")
        return
    if not out:
        raise DhsimError("--csv: the file name is empty; give a name to write to")
    path = Path(out)
    if path.is_dir():
        raise DhsimError(printable(f"--csv {out}: is a folder; give a file name to write to"))
    if path.exists() and not args.force:
        raise DhsimError(printable(f"--csv {out}: the file exists; --force replaces it"))


def cmd_program(args: argparse.Namespace) -> int:
    _check_csv_target(args)
    robot, _ = load_robot(args.robot)
    program = robot.program(args.program)
    start = start_joints(robot, args.start)
    trajectory = sample(robot, program, args.rate, start)
    problems = check_path(trajectory)
    if args.json:
        print(run_json(trajectory, problems))
    elif args.csv == "-":  # stdout carries the CSV: the report never goes there
        to_stderr(format_run(trajectory, problems))
    else:
        print(format_run(trajectory, problems))
    if args.csv is not None:
        from dhsim_tui.core.motion.trajectory_csv import csv_pieces

        pieces = csv_pieces(trajectory)
        if args.csv == "-":
            for piece in pieces:
                sys.stdout.write(piece)
        else:
            encoded = (piece.encode("utf-8") for piece in pieces)
            write_file(args.csv, encoded, overwrite=args.force)
            wrote = printable(f"wrote {args.csv}")
            if args.json:  # stdout carries the JSON
                to_stderr(wrote)
            else:
                print(wrote)
    if args.plot:
        from dhsim_tui.render.program_plot import plot_text  # plotext: loaded when asked for

        size = shutil.get_terminal_size((100, 32))
        colour = _coloured()
        ascii = wants_ascii(original_environ(), force=None)
        rows = max(16, size.lines - 2)
        print(plot_text(trajectory, problems, size.columns, rows, colour=colour, ascii=ascii))
    return EXIT_PROBLEMS if problems else 0


def _coloured() -> bool:
    """A plot in colour: on a terminal, unless NO_COLOR is set."""
    try:
        return os.isatty(sys.stdout.fileno()) and "NO_COLOR" not in os.environ
    except (AttributeError, OSError, ValueError):
        return False


def subparsers(parser_class: type[argparse.ArgumentParser]) -> dict[str, argparse.ArgumentParser]:
    """The command's parser (``parser_class`` reports errors in one line)."""
    parser = parser_class(
        prog="dhsim run",
        description="Play a robot's program as a controller would (joint moves, linear "
        "moves, waits) and check its path: joint limits, joint speeds, reach and IK "
        "jumps in linear moves, singularities, frames below the floor. Exit status 0: "
        "clean; 3: problems found; 2: bad input.",
        epilog=CSV_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("robot", help="a robot file or a bundled robot's name")
    parser.add_argument("program", help="the name of one of the robot's programs")
    parser.add_argument(
        "--rate",
        type=rate_value,
        default=DEFAULT_RATE,
        metavar="HZ",
        help=f"samples a second ({MIN_RATE:g} to {MAX_RATE:g}; default {DEFAULT_RATE:g})",
    )
    parser.add_argument(
        "--from",
        dest="start",
        metavar="V1,V2,...|POSE",
        help="where the arm starts: joint values or a pose name; default: home",
    )
    parser.add_argument(
        "--csv",
        metavar="FILE",
        help="write every sample to FILE as CSV ('-': stdout, the report then on stderr)",
    )
    parser.add_argument("--force", action="store_true", help="replace the --csv file if it exists")
    shown = parser.add_mutually_exclusive_group()
    shown.add_argument("--json", action="store_true", help="print one JSON object")
    shown.add_argument(
        "--plot", action="store_true", help="draw the joints and the tool's speed against time"
    )
    parser.set_defaults(func=cmd_program)
    return {"run": parser}
