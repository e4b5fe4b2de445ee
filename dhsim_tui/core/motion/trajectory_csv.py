"""A trajectory as CSV, the exchange format (``dhsim run --csv``), and such a
CSV read back as a program (``dhsim import --program``).

The file starts with the header row, then one row per sample, and nothing
else: ``pandas.read_csv`` and a spreadsheet take the first line as the
column names::

    time,step,move,q1,q2,q3,q4,q5,q6,x,y,z,o,a,t,mu

``time`` in seconds, ``step`` 1-based, ``move`` joint, linear or wait,
``q1``... in degrees (revolute) or the robot's unit (prismatic), ``x, y, z``
the tool point in the world (robot's unit), ``o, a, t`` its orientation
(degrees, the pose panel's OAT) and ``mu`` the manipulability
(dimensionless); :func:`column_units` gives them per column (``dhsim run
--json`` prints them, ``dhsim run --help`` names them). Numbers carry 12
significant digits. Files written before the header came first start with
a ``#`` comment line naming the robot, the program, the rate and the units.

Reading one back (:func:`program_from_csv`) needs the header row and a
column ``q1``... per joint; a ``#`` line is a comment, wherever it is, and
the joint units a dhsim comment line names (``units: ... q1 deg``: the old
files') must be the robot's. With a ``step``
column, each run of rows of one step becomes one step: a wait (its
``move`` is wait) as long as the run lasts, else a joint move to the
run's last row; without one, every row is a joint move to its joints
(a row equal to the one before is dropped). With a ``time`` column a
joint move's speed is the percentage of the top speeds that makes it
take as long as it did in the file (at most 100 %).
"""

from __future__ import annotations

import csv
import io
import math
import re
from collections.abc import Iterator

import numpy as np

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.kinematics import read_out
from dhsim_tui.core.model.profiles import joint_profile
from dhsim_tui.core.model.program import MAX_STEPS, MAX_WAIT, Program, Step, check_values
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable, shortened
from dhsim_tui.core.motion.trajectory import Trajectory

#: significant digits written
DIGITS = 12
#: decimals a step's joint values keep when read back (deg or robot units)
DECIMALS = 6
#: the slowest joint move a matched speed gives (percent)
MIN_PERCENT = 0.1


def columns(robot: Robot) -> list[str]:
    return [
        "time",
        "step",
        "move",
        *(f"q{i}" for i in range(1, robot.dof + 1)),
        *"xyz",
        *"oat",
        "mu",
    ]


def column_units(robot: Robot) -> dict[str, str | None]:
    """Every column's unit (None: a count, a word or a pure number)."""
    return {
        "time": "s",
        "step": None,
        "move": None,
        **{f"q{i}": joint.unit(robot.units) for i, joint in enumerate(robot.joints, start=1)},
        **dict.fromkeys("xyz", robot.units),
        **dict.fromkeys("oat", "deg"),
        "mu": None,
    }


def _number(value: float) -> str:
    text = f"{value:.{DIGITS}g}"
    return "0" if text in ("-0", "0") else text


#: rows formatted at a time by :func:`csv_pieces`
ROWS_PER_PIECE = 4096


def csv_pieces(trajectory: Trajectory) -> Iterator[str]:
    """The trajectory as CSV text (see the module's description), in pieces
    of :data:`ROWS_PER_PIECE` rows, so a long run is written as it is
    formatted instead of held whole."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(columns(trajectory.robot))
    mu = trajectory.mu
    for first in range(0, len(trajectory.time), ROWS_PER_PIECE):
        last = first + ROWS_PER_PIECE
        times = np.round(trajectory.time[first:last], 9).tolist()
        steps = trajectory.step[first:last].tolist()
        moves = trajectory.move[first:last].tolist()
        mus = mu[first:last].tolist()
        poses = trajectory.pose[first:last]
        for i, q in enumerate(trajectory.q[first:last].tolist()):
            end = read_out(poses[i])
            numbers = [*q, *end.xyz, *end.oat, mus[i]]
            writer.writerow([_number(times[i]), steps[i], moves[i], *(_number(v) for v in numbers)])
        yield out.getvalue()
        out.seek(0)
        out.truncate()
    if out.tell():  # no samples: the header row alone
        yield out.getvalue()


def csv_text(trajectory: Trajectory) -> str:
    """The trajectory as CSV text, whole (see :func:`csv_pieces`)."""
    return "".join(csv_pieces(trajectory))


# -- reading a trajectory back as a program -------------------------------------------
_UNIT = re.compile(r"\bq(\d+) ([a-z]+)\b")


def program_from_csv(robot: Robot, text: str, name: str, source: str = "<csv>") -> Program:
    """The program a trajectory CSV replays on ``robot`` (see the module's
    description); a :class:`DhsimError` naming the row and the column for
    anything that does not fit the robot."""
    where = printable(shortened(source))
    lines = text.removeprefix("\ufeff").splitlines()
    _check_units(robot, lines, where)
    rows = [row for row in csv.reader(line for line in lines if not line.startswith("#"))]
    rows = [
        (number, row) for number, row in enumerate(rows, start=1) if any(c.strip() for c in row)
    ]
    if not rows:
        raise DhsimError(f"{where}: no header row (time, step, move, q1, ...)")
    header = [cell.strip().lower() for cell in rows[0][1]]
    wanted = [f"q{i}" for i in range(1, robot.dof + 1)]
    missing = [column for column in wanted if column not in header]
    if missing:
        raise DhsimError(
            f"{where}: no column {missing[0]} (the robot has {robot.dof} joints: "
            f"q1 to q{robot.dof} are needed)"
        )
    extra = [c for c in header if re.fullmatch(r"q\d+", c) and c not in wanted]
    if extra:
        raise DhsimError(f"{where}: column {extra[0]}, but the robot has {robot.dof} joints")
    records = [_record(robot, header, wanted, number, row, where) for number, row in rows[1:]]
    if not records:
        raise DhsimError(f"{where}: no rows after the header")
    steps = _steps(robot, records, "step" in header)
    if len(steps) > MAX_STEPS:
        raise DhsimError(
            f"{where}: {len(steps)} steps, more than a program's {MAX_STEPS}; "
            "keep fewer rows (every tenth, say)"
        )
    return Program(name, tuple(steps))


def _check_units(robot: Robot, lines: list[str], where: str) -> None:
    """A dhsim comment line's joint units must be the robot's (the comment
    line an old file starts with, or one anywhere else)."""
    for line in lines:
        if not line.startswith("#"):
            continue
        for number, unit in _UNIT.findall(line.partition("units:")[2]):
            index = int(number) - 1
            if 0 <= index < robot.dof:
                expected = robot.joints[index].unit(robot.units)
                if unit != expected:
                    raise DhsimError(
                        f"{where}: q{number} is in {unit} in the file, "
                        f"but in {expected} on {printable(shortened(robot.name))}"
                    )


def _record(robot, header, wanted, number, row, where):
    """(time or None, step or None, move, joint values) of one row, checked."""

    def cell(column: str) -> str:
        index = header.index(column)
        if index >= len(row):
            raise DhsimError(f"{where}: row {number}: no value for {column}")
        return row[index].strip()

    def value(column: str) -> float:
        text = cell(column)
        try:
            number_ = float(text)
        except ValueError:
            shown = printable(repr(shortened(text)))
            raise DhsimError(f"{where}: row {number}, {column}: {shown} is not a number") from None
        if not math.isfinite(number_):
            raise DhsimError(f"{where}: row {number}, {column}: not a finite number")
        return number_

    q = check_values(robot, [value(c) for c in wanted], f"{where}: row {number}")
    time = value("time") if "time" in header else None
    step = value("step") if "step" in header else None
    move = cell("move").lower() if "move" in header else "joint"
    return time, step, move, q


def _steps(robot: Robot, records: list, by_step: bool) -> list[Step]:
    """Group the rows into steps: by the step column, or by the joints (a run
    of equal rows is one waypoint, and a wait for as long as it lasts). A
    move's target is its last row, or the pose a wait right after it holds
    (exact: the move's end)."""
    groups: list[tuple[object, list]] = []
    for record in records:
        key = record[1] if by_step else record[3]
        if groups and groups[-1][0] == key:
            groups[-1][1].append(record)
        else:
            groups.append((key, [record]))
    steps: list[Step] = []
    q, last_time = _rounded(robot, records[0][3]), records[0][0]
    for index, (_, rows) in enumerate(groups):
        arrived = rows[-1][0] if by_step else rows[0][0]
        took = None if last_time is None else arrived - last_time
        goal = _rounded(robot, rows[-1][3])
        following = groups[index + 1][1] if index + 1 < len(groups) else None
        if by_step and following and following[0][2] == "wait":
            goal = _rounded(robot, following[0][3])  # the pose the wait holds: the move's end
        if by_step and rows[0][1] == 0:
            pass  # step 0: a program without steps, its start alone
        elif by_step and rows[0][2] == "wait":
            steps.append(_wait(took or 0.0))
        elif goal != q:
            steps.append(Step("joint", goal, speed=matched_speed(robot, q, goal, took)))
            q = goal
        if not by_step and last_time is not None and rows[-1][0] > rows[0][0]:
            steps.append(_wait(rows[-1][0] - rows[0][0]))
        last_time = rows[-1][0]
    return steps


def _rounded(robot: Robot, q: tuple[float, ...]) -> tuple[float, ...]:
    """Joint values to :data:`DECIMALS` places, kept within the limits."""
    return tuple(
        min(max(round(v, DECIMALS) + 0.0, j.min), j.max)
        for v, j in zip(q, robot.joints, strict=True)
    )


def _wait(seconds: float) -> Step:
    return Step("wait", seconds=round(min(max(seconds, 0.0), MAX_WAIT), 9))


def matched_speed(robot: Robot, start, goal, seconds: float | None) -> float | None:
    """The joint move's speed (percent) that takes about ``seconds`` (None:
    the default, also when even 100 % is slower)."""
    if seconds is None or not seconds > 0.0:
        return None
    if joint_profile(robot, start, goal, 100.0).duration >= seconds:
        return None
    low, high = MIN_PERCENT, 100.0
    if joint_profile(robot, start, goal, low).duration <= seconds:
        return low
    for _ in range(40):  # bisection: the duration falls as the speed rises
        middle = 0.5 * (low + high)
        if joint_profile(robot, start, goal, middle).duration > seconds:
            low = middle
        else:
            high = middle
    return round(high, 2)
