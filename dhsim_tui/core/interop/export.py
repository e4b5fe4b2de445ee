"""A robot written for other tools: URDF, a CSV D-H table or JSON (``dhsim export``).

:func:`export_text` gives the text, :func:`write_export` writes it atomically.
Every format carries the whole robot; numbers are written so they read back
as the same float (``repr`` or :func:`~dhsim_tui.core.model.validation.fmt`).

URDF: :mod:`dhsim_tui.core.interop.urdf_export`. Besides the URDF's links and joints
it holds the whole robot, as the JSON below, in a comment other tools ignore,
so ``dhsim import`` gives back the very robot while the joints still match.

CSV (format ``dhsim-dh-table 1``)
---------------------------------
UTF-8 text, lines ending in ``\\n``. First, comment lines, each
``# KEY = VALUE`` (a ``#``, one space, the key, `` = ``, the value to the
end of the line), in this order::

    # format = dhsim-dh-table 1
    # name = "Puma 560"
    # convention = standard
    # units = mm
    # base_height = 0
    # base_z = +z
    # base_x = +x
    # base_xyz = 0, 0, 0
    # base_rpy = 0, 0, 0
    # tool_xyz = 0, 0, 0
    # tool_rpy = 0, 0, 0
    # pose "ready" = 0, 90, -90, 0, 0, 0

- ``name``: a JSON string (``json.loads`` of the value);
- ``convention`` (``standard``/``modified``), ``units`` (``mm``, ``cm``,
  ``m``, ``in``), ``base_z``, ``base_x`` (``+x`` ... ``-z``): bare words;
- ``base_height``: one number; ``base_xyz``, ``base_rpy``, ``tool_xyz``,
  ``tool_rpy``: three numbers separated by ``, `` (xyz in the robot's unit,
  rpy = roll, pitch, yaw in degrees, R = Rz(yaw)·Ry(pitch)·Rx(roll));
- ``pose``: one line per named pose, in order: ``# pose `` then the pose's
  name as a JSON string, then `` = `` and one joint value per joint
  separated by ``, ``. Read the name with
  ``json.JSONDecoder().raw_decode(line, 7)``; the rest is `` = v1, v2, ...``.

Every number is a decimal float literal Python's ``float()`` reads back to
the very value (``431.8``, ``-90``, ``1e+06``, ``0.30000000000000004``).
A reader should ignore keys it does not know (later versions may add some).

Then the table, written with the ``csv`` module (comma separated, no cell
needs quoting): a header row, exactly::

    joint,type,theta (deg),d (mm),a (mm),alpha (deg),offset (deg|mm),min (deg|mm),max (deg|mm)

with the robot's unit in place of ``mm``; ``offset``, ``min`` and ``max``
are in degrees on a revolute row and in the robot's unit on a prismatic
one. Then one row per joint, in order: ``joint`` is its number from 1,
``type`` is ``R`` (revolute) or ``P`` (prismatic), then the numbers. As in
dhsim, theta (revolute) or d (prismatic) is the D-H variable's value at
home, the joint value is q with theta = q + offset (d = q + offset), and
min/max/poses are in q. The first line that does not begin with ``#`` is
the header; no comment follows it. A D-H table has no programs: they are
the JSON's and the URDF's (a program's trajectory is ``dhsim run --csv``).

JSON (format ``dhsim-robot`` version 1)
---------------------------------------
One object, keys in a fixed order: ``format``, ``version``, ``name``,
``units`` ({length, angle}), ``convention``, ``parameter_order``,
``joint_value``, ``base`` ({height, z, x, xyz, rpy}), ``tool`` ({xyz, rpy}),
``joints`` (objects: type, then the parameters in ``parameter_order``,
then ``vmax`` and ``amax`` when the joint has them), ``poses`` (name ->
joint values, in order) and ``programs`` (name -> steps, as the robot
file's ``[programs]`` table). Finite numbers only.
"""

from __future__ import annotations

import csv
import io
import json
import os
from pathlib import Path

from dhsim_tui.core.files.atomicfile import write_file
from dhsim_tui.core.files.formats import EXPORT_FORMATS
from dhsim_tui.core.interop.urdf_export import dhsim_fields, to_urdf
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.core.model.validation import fmt as number_text

CSV_FORMAT = "dhsim-dh-table 1"
PARAMETER_ORDER: tuple[str, ...] = ("theta", "d", "a", "alpha", "offset", "min", "max")


# -- the one entry point --------------------------------------------------------------
def export_text(robot: Robot, fmt: str) -> str:
    """The robot as ``fmt`` (one of :data:`EXPORT_FORMATS`) text."""
    writers = {"urdf": to_urdf, "csv": to_csv, "json": to_json}
    if not isinstance(fmt, str) or fmt not in writers:
        shown = printable(repr(fmt))
        raise DhsimError(f"export format {shown}: expected one of {', '.join(EXPORT_FORMATS)}")
    return writers[fmt](robot)


def write_export(
    robot: Robot, fmt: str, path: str | os.PathLike[str], *, overwrite: bool = False
) -> Path:
    """Write :func:`export_text` to ``path`` atomically and return ``path``
    (see :func:`~dhsim_tui.core.files.atomicfile.write_file`)."""
    return write_file(path, export_text(robot, fmt).encode("utf-8"), overwrite=overwrite)


# -- CSV --------------------------------------------------------------------------------
def _numbers(values) -> str:
    return ", ".join(number_text(float(v)) for v in values)


def csv_header(units: str) -> list[str]:
    """The CSV table's header row for a robot in ``units``."""
    both = f"deg|{units}"
    return [
        "joint",
        "type",
        "theta (deg)",
        f"d ({units})",
        f"a ({units})",
        "alpha (deg)",
        f"offset ({both})",
        f"min ({both})",
        f"max ({both})",
    ]


def to_csv(robot: Robot) -> str:
    """The D-H table as CSV, the rest of the robot in ``# `` lines before it
    (the format is in the module's docstring)."""
    lines = [
        f"format = {CSV_FORMAT}",
        f"name = {json.dumps(robot.name, ensure_ascii=False)}",
        f"convention = {robot.convention}",
        f"units = {robot.units}",
        f"base_height = {number_text(float(robot.base_height))}",
        f"base_z = {robot.base_z}",
        f"base_x = {robot.base_x}",
        f"base_xyz = {_numbers(robot.base_xyz)}",
        f"base_rpy = {_numbers(robot.base_rpy)}",
        f"tool_xyz = {_numbers(robot.tool.xyz)}",
        f"tool_rpy = {_numbers(robot.tool.rpy)}",
    ]
    for name, values in robot.poses:
        lines.append(f"pose {json.dumps(name, ensure_ascii=False)} = {_numbers(values)}")
    out = io.StringIO()
    out.write("".join(f"# {line}\n" for line in lines))
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(csv_header(robot.units))
    for number, joint in enumerate(robot.joints, start=1):
        numbers = (getattr(joint, name) for name in PARAMETER_ORDER)
        writer.writerow(
            [
                str(number),
                "R" if joint.is_revolute else "P",
                *(number_text(float(v)) for v in numbers),
            ]
        )
    return out.getvalue()


# -- JSON -------------------------------------------------------------------------------
def to_json(robot: Robot) -> str:
    """The whole robot as JSON (see the module's docstring): the object a
    URDF export stores in its comment, programs and top speeds included."""
    data = dhsim_fields(robot)
    return json.dumps(data, indent=2, allow_nan=False, ensure_ascii=False) + "\n"
