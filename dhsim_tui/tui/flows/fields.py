"""The editor's questions about one robot field (name, units, base, tool, a pose).

Each returns the edited robot, or None when the user cancelled; a choice the
core refuses raises DhsimError, which the editor shows.
"""

from __future__ import annotations

from textual.app import App

from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import AXES, CONVENTIONS, UNITS, Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.core.model.validation import perpendicular_axes
from dhsim_tui.tui.screens.dialogs import Choice
from dhsim_tui.tui.screens.editor_table import FIELD_LABELS, number, numbers
from dhsim_tui.tui.screens.value_entry import ValueEntry

CHOICE_SETTERS = {
    "units": editing.set_units,
    "convention": editing.set_convention,
    "base_z": editing.set_base_z,
    "base_x": editing.set_base_x,
}


async def ask_field(app: App, robot: Robot, key: str) -> Robot | None:
    """Ask for a new value of ``key`` (a FIELD_ROWS key or ``pose:NAME``)."""
    if key in CHOICE_SETTERS:
        choices = {
            "units": [
                (u, u + ("  (lengths are converted)" if u != robot.units else "")) for u in UNITS
            ],
            "convention": [(c, c) for c in CONVENTIONS],
            "base_z": [(a, a) for a in AXES],
            "base_x": [(a, a) for a in perpendicular_axes(robot.base_z)],
        }[key]
        value = await app.push_screen_wait(Choice(FIELD_LABELS[key], choices, getattr(robot, key)))
        return None if value is None else CHOICE_SETTERS[key](robot, value)
    if key == "name":
        entry = ValueEntry(
            "robot name",
            robot.name,
            "any text · enter sets · escape cancels",
            lambda text: editing.set_name(robot, text),
        )
    elif key == "base_height":
        entry = ValueEntry(
            f"base height ({robot.units})",
            numbers((robot.base_height,)),
            "frame 0 above the floor, >= 0",
            lambda text: editing.set_base_height(robot, editing.parse_number(text, "base height")),
        )
    elif key in ("base_xyz", "base_rpy"):
        part = key.removeprefix("base_")
        entry = ValueEntry(
            FIELD_LABELS[key] + (f" ({robot.units})" if part == "xyz" else ""),
            numbers(getattr(robot, key)),
            "frame 0's position: x, y, z in the world"
            if part == "xyz"
            else "roll, pitch, yaw in degrees, after base z and base x",
            lambda text: editing.set_base(
                robot, **{part: editing.parse_numbers(text, 3, FIELD_LABELS[key])}
            ),
        )
    elif key in ("tool_xyz", "tool_rpy"):
        part = key.removeprefix("tool_")
        entry = ValueEntry(
            FIELD_LABELS[key] + (f" ({robot.units})" if part == "xyz" else ""),
            numbers(getattr(robot.tool, part)),
            "three numbers: x, y, z" if part == "xyz" else "roll, pitch, yaw in degrees",
            lambda text: editing.set_tool(
                robot, **{part: editing.parse_numbers(text, 3, FIELD_LABELS[key])}
            ),
        )
    elif key.startswith("pose:"):
        name = key.removeprefix("pose:")
        shown = printable(name)
        entry = ValueEntry(
            f"pose {shown}",
            numbers(robot.pose(name)),
            f"{robot.dof} joint values, separated by commas",
            lambda text: editing.set_pose(
                robot, name, editing.parse_numbers(text, robot.dof, f"pose {shown}")
            ),
        )
    else:
        return None
    return await app.push_screen_wait(entry)


async def ask_new_pose_name(app: App, robot: Robot) -> str | None:
    """A name for a new pose: not empty, not one the robot has."""

    def check(text: str) -> str:
        name = text.strip()
        if not name:
            raise DhsimError("a pose needs a name")
        if name in robot.pose_names:
            raise DhsimError(f"there is already a pose named {name!r}")
        return name

    return await app.push_screen_wait(
        ValueEntry(
            "new pose",
            f"pose{len(robot.poses) + 1}",
            "a name; the pose starts at home",
            check,
        )
    )


async def ask_joint_field(
    app: App, robot: Robot, index: int, name: str
) -> tuple[Robot, str] | None:
    """A new value for one D-H number of one joint: (robot, what changed)."""
    joint = robot.joints[index]
    label = f"joint {index + 1} {name}"
    angle = name in ("theta", "alpha") or (name in ("min", "max", "offset") and joint.is_revolute)
    unit = "deg" if angle else robot.units

    def check(text: str) -> Robot:
        return editing.set_joint_field(robot, index, name, editing.parse_number(text))

    new = await app.push_screen_wait(
        ValueEntry(
            f"{label} ({unit})",
            number(getattr(joint, name)),
            f"a number in {unit} · enter sets · escape cancels",
            check,
        )
    )
    if new is None:
        return None
    return new, f"{label} = {number(getattr(new.joints[index], name))} {unit}"
