"""``dhsim import``, ``export`` and ``convert``: robots in and out of dhsim.

A thin shell over :mod:`dhsim_tui.core.interop.importer`, :mod:`dhsim_tui.core.interop.export`
and :mod:`dhsim_tui.core.interop.convert`. Each prints its result on stdout unless
``-o FILE`` is given; a file that exists is refused unless ``--force`` (a
robot file is then updated in place, its comments kept). Remarks go to
stderr when stdout carries the result, so ``dhsim export puma560 --format
urdf > puma.urdf`` writes nothing else into the file.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path

from dhsim_tui.cli import streams
from dhsim_tui.core.files.formats import EXPORT_FORMATS
from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.files.robotfile import dumps, save
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import CONVENTIONS, UNITS, Robot
from dhsim_tui.core.model.text import printable, shortened


def robot_text(robot: Robot, header: tuple[str, ...] = ()) -> str:
    """A robot file's text, with ``header`` as comment lines on top."""
    comments = "".join(f"# {printable(line)}\n" for line in header)
    return comments + ("\n" if comments else "") + dumps(robot)


def _write_robot(robot: Robot, header: tuple[str, ...], out: str | None, force: bool) -> None:
    text = robot_text(robot, header)
    if out is None:
        sys.stdout.write(text)
        return
    path = Path(out)
    save(robot, path, expect=... if force else None, base_text=text)
    print(printable(f"wrote {path}"))


#: what -o '' gets (the same words as the core's atomic writer)
EMPTY_NAME = "-o: the file name is empty; give a name to write to"


def _check_output_name(out: str | None) -> None:
    """``-o ''`` is an empty name (``Path('')`` would be the working folder)."""
    if out is not None and not out:
        raise DhsimError(EMPTY_NAME)


def _check_robot_output(out: str | None, force: bool) -> None:
    """Before any work: ``-o`` names a .toml file, and one that exists only with --force."""
    _check_output_name(out)
    if out is None:
        return
    if Path(out).suffix != ".toml":
        raise DhsimError(printable(f"-o {out}: a robot file's name ends in .toml"))
    if not force and Path(out).exists():
        raise DhsimError(
            printable(f"{out}: the file exists; --force replaces it (keeping its comments)")
        )


def _tell(lines: tuple[str, ...], to_stderr: bool) -> None:
    for line in lines:
        if to_stderr:  # stdout carries the result: a remark never goes there
            streams.to_stderr(printable(line))
        else:
            print(printable(line))


# Each command loads its part of the core when it runs: ``dhsim`` itself
# (the simulator) starts through this module and should not pay for them.


def cmd_import(args: argparse.Namespace) -> int:
    if args.program:
        return _import_program(args)
    if args.robot is not None:
        raise DhsimError(
            printable(f"{shortened(args.robot)}: a second file is read only with --program")
        )
    from dhsim_tui.core.interop.importer import import_file

    _check_robot_output(args.output, args.force)
    result = import_file(
        args.file,
        tip=args.tip,
        base=args.base,
        convention=args.convention,
        units=args.units,
        name=args.name,
    )
    _tell(result.notes, to_stderr=args.output is None)
    _write_robot(result.robot, result.header, args.output, args.force)
    return 0


#: the largest trajectory CSV ``import --program`` reads (an hour at 100 Hz of
#: a 7-joint arm is about 60 MB)
MAX_PROGRAM_CSV_BYTES = 128 * 1024 * 1024


def _import_program(args: argparse.Namespace) -> int:
    """``dhsim import --program FILE.csv ROBOT``: the robot file with the
    trajectory added as a program of joint moves (waits kept; see
    core.motion.trajectory_csv), its comments kept."""
    from dhsim_tui.core.files.atomicfile import read_file
    from dhsim_tui.core.files.robotfile import render
    from dhsim_tui.core.motion.trajectory_csv import program_from_csv

    if args.robot is None:
        raise DhsimError(
            "--program: name the robot to add it to (dhsim import --program FILE ROBOT)"
        )
    for option in ("tip", "base", "convention", "units"):
        if getattr(args, option) is not None:
            raise DhsimError(f"--{option} does not go with --program")
    _check_robot_output(args.output, args.force)
    robot, path = load_robot(args.robot)
    source = Path(args.file)
    name = args.name if args.name is not None else source.stem
    if name in robot.program_names:
        raise DhsimError(
            printable(
                f"{shortened(robot.name)} has a program named {shortened(name)!r} already; "
                "give the new one another with --name"
            )
        )
    raw, _ = read_file(source, MAX_PROGRAM_CSV_BYTES)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise DhsimError(printable(f"{args.file}: not UTF-8 text")) from None
    program = program_from_csv(robot, text, name, args.file)
    updated = replace(robot, programs=(*robot.programs, program))
    _tell(
        (f"{shortened(robot.name)}: program {shortened(name)!r}, {len(program.steps)} steps",),
        to_stderr=args.output is None,
    )
    original = path.read_text(encoding="utf-8")
    if args.output is None:
        sys.stdout.write(render(updated, original))
        return 0
    save(updated, Path(args.output), expect=... if args.force else None, base_text=original)
    print(printable(f"wrote {args.output}"))
    return 0


def cmd_export(args: argparse.Namespace) -> int:
    from dhsim_tui.core.interop.export import export_text, write_export

    _check_output_name(args.output)
    robot, _ = load_robot(args.robot)
    if args.output is None:
        sys.stdout.write(export_text(robot, args.format))
        return 0
    path = write_export(robot, args.format, Path(args.output), overwrite=args.force)
    print(printable(f"wrote {path}"))
    return 0


def cmd_convert(args: argparse.Namespace) -> int:
    from dhsim_tui.core.interop.convert import convert

    _check_robot_output(args.output, args.force)
    robot, path = load_robot(args.robot)
    converted = convert(robot, args.convention)
    note = (
        f"{robot.convention} to {args.convention} D-H"
        if converted is not robot
        else f"already {args.convention} D-H: unchanged"
    )
    name = shortened(robot.name)
    _tell((f"{name}: {note}",), to_stderr=args.output is None)
    header = (f"{name}: converted by dhsim from {path.name} ({note}).",)
    _write_robot(converted, header, args.output, args.force)
    return 0


def _output_options(parser: argparse.ArgumentParser, what: str) -> None:
    parser.add_argument(
        "-o", "--output", metavar="FILE", help=f"write {what} to FILE (default: stdout)"
    )
    parser.add_argument(
        "--force",
        action="store_true",
        help="replace FILE if it exists (a robot file keeps its comments)",
    )


def subparsers(parser_class: type[argparse.ArgumentParser]) -> dict[str, argparse.ArgumentParser]:
    """The three commands' parsers (``parser_class`` reports errors in one line)."""
    imp = parser_class(
        prog="dhsim import",
        description="Make a dhsim robot from a URDF's serial chain or a D-H table in CSV; "
        "with --program, add a trajectory CSV (dhsim run --csv) to a robot as a program.",
    )
    imp.add_argument("file", help="a .urdf or .csv file")
    imp.add_argument("robot", nargs="?", help="with --program: the robot to add the program to")
    imp.add_argument(
        "--program",
        action="store_true",
        help="read FILE as a trajectory (time, step, move, q1...) and write ROBOT's file with "
        "it added as a program: a joint move to each step's last row, at the speed that "
        "takes as long (waits kept); without a step column, a joint move to each row",
    )
    imp.add_argument(
        "--tip", metavar="LINK", help="URDF: the chain's last link (needed for a tree)"
    )
    imp.add_argument(
        "--base", metavar="LINK", help="URDF: the chain's first link (default: the root)"
    )
    imp.add_argument(
        "--convention",
        choices=CONVENTIONS,
        help="the D-H convention of the robot made (default: standard for a URDF, the "
        "CSV's '# convention' line or standard); a CSV without that line is read as this",
    )
    imp.add_argument(
        "--units",
        choices=tuple(UNITS),
        help="length unit of the robot made (default: m for a URDF, the CSV header's or mm)",
    )
    imp.add_argument(
        "--name",
        help="the robot's name (default: the URDF's or the file's); with --program, the "
        "program's (default: the file's name without .csv)",
    )
    _output_options(imp, "the robot file (.toml)")
    imp.set_defaults(func=cmd_import)
    exp = parser_class(
        prog="dhsim export", description="Write a robot as URDF, a CSV D-H table, or JSON."
    )
    exp.add_argument("robot", help="a robot file or a bundled robot's name")
    exp.add_argument("--format", required=True, choices=EXPORT_FORMATS, help="the output format")
    _output_options(exp, "the result")
    exp.set_defaults(func=cmd_export)
    conv = parser_class(
        prog="dhsim convert",
        description="The same robot in the other D-H convention "
        "(the same pose at every joint value).",
    )
    conv.add_argument("robot", help="a robot file or a bundled robot's name")
    conv.add_argument("--convention", required=True, choices=CONVENTIONS)
    _output_options(conv, "the robot file (.toml)")
    conv.set_defaults(func=cmd_convert)
    return {"import": imp, "export": exp, "convert": conv}
