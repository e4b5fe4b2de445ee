"""``dhsim workspace``: where a robot's tool can go.

Draws N joint vectors uniformly within the limits (seeded: repeatable), puts
them through batch FK (:mod:`dhsim_tui.core.analysis.workspace`) and prints the
bounding box of the tool positions, the largest distance from frame 0's
origin reached against the reach bound, and the largest horizontal radius;
``--json`` prints one object instead. Millions of samples are summarised
chunk by chunk, so memory stays flat.
"""

from __future__ import annotations

import argparse
import json

from dhsim_tui.core.analysis.workspace import (
    DEFAULT_SAMPLES,
    MAX_SAMPLES,
    WorkspaceSummary,
    check_sample_count,
    sample_summary,
)
from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import LENGTH_DECIMALS, Robot
from dhsim_tui.core.model.text import counted, printable, shortened

#: the largest seed accepted (numpy's generators take any non-negative integer)
MAX_SEED = 2**63 - 1


def _whole_number(text: str) -> int:
    """ASCII digits only: int() would also read ``١`` (Arabic-Indic) as 1."""
    try:
        if "_" in text or not text.isascii():  # int() would read 1_0 as 10
            raise ValueError
        return int(text.strip())
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{shortened(text)!r} is not a whole number (ASCII digits 0-9)"
        ) from None


def sample_count(text: str) -> int:
    """``--n``: a whole number of samples, 1 to MAX_SAMPLES."""
    try:
        return check_sample_count(_whole_number(text))
    except DhsimError:
        raise argparse.ArgumentTypeError(
            f"{shortened(text)!r}: give a whole number of samples from 1 to {MAX_SAMPLES}"
        ) from None


def seed_value(text: str) -> int:
    """``--seed``: a whole number from 0 to 2^63 - 1."""
    value = _whole_number(text)
    if not 0 <= value <= MAX_SEED:
        raise argparse.ArgumentTypeError(
            f"{shortened(text)!r}: give a whole number from 0 to {MAX_SEED}"
        )
    return value


def format_workspace(robot: Robot, summary: WorkspaceSummary, seed: int) -> str:
    """Aligned lines: the samples, the box per axis, reach and radius, with units."""
    places = LENGTH_DECIMALS[robot.units]
    unit = robot.units

    def num(value: float) -> str:
        return f"{round(value, places) + 0.0:.{places}f}"

    lows, highs = [num(v) for v in summary.xyz_min], [num(v) for v in summary.xyz_max]
    width = max(len(cell) for cell in (*lows, *highs, num(summary.reach)))
    label = len("reached by samples")
    box = [
        f"{axis:<{label}}  {lo:>{width}} .. {hi:>{width}} {unit}"
        for axis, lo, hi in zip("xyz", lows, highs, strict=True)
    ]
    figures = [
        f"{'reach':<{label}}  {num(summary.reach):>{width}} {unit}"
        f"   the farthest the tool gets from frame 0's origin within the limits",
        f"{'reached by samples':<{label}}  {num(summary.reach_reached):>{width}} {unit}"
        f"   the farthest of these samples; link lengths' sum {num(summary.reach_bound)} {unit}",
        f"{'horizontal radius':<{label}}  {num(summary.horizontal_radius):>{width}} {unit}"
        "   from the vertical through frame 0's origin",
    ]
    head = [
        printable(shortened(robot.name)),
        f"{counted(summary.count, 'random joint vector')} within the limits (seed {seed}); "
        "tool positions, world coordinates",
    ]
    return "\n".join([*head, *box, *figures])


def workspace_json(robot: Robot, summary: WorkspaceSummary, seed: int) -> str:
    return json.dumps({"robot": robot.name, "seed": seed, **summary.as_dict()})


def cmd_workspace(args: argparse.Namespace) -> int:
    robot, _ = load_robot(args.robot)
    summary = sample_summary(robot, args.n, args.seed)
    if args.json:
        print(workspace_json(robot, summary, args.seed))
    else:
        print(format_workspace(robot, summary, args.seed))
    return 0


def subparsers(parser_class: type[argparse.ArgumentParser]) -> dict[str, argparse.ArgumentParser]:
    """The command's parser (``parser_class`` reports errors in one line)."""
    parser = parser_class(
        prog="dhsim workspace",
        description="Sample the workspace: tool positions for random joint values within "
        "the limits; print their bounding box, the reach reached and the horizontal radius.",
    )
    parser.add_argument("robot", help="a robot file or a bundled robot's name")
    parser.add_argument(
        "--n",
        type=sample_count,
        default=DEFAULT_SAMPLES,
        metavar="N",
        help=f"how many joint vectors (1 to {MAX_SAMPLES}; default {DEFAULT_SAMPLES})",
    )
    parser.add_argument(
        "--seed",
        type=seed_value,
        default=0,
        metavar="S",
        help="the random generator's seed (default 0): the same seed, the same samples",
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(func=cmd_workspace)
    return {"workspace": parser}
