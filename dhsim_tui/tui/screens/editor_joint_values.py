"""The editor's joint values: the D-H variable (theta, or d for a prismatic
joint), the offset, the home joint value between them, and a joint's type.

The table holds each joint's D-H variable at home; its home joint value is
``theta - offset`` (``d - offset``), shown live in the ``home`` column. So a
new offset changes one of the two, and the editor asks which:

- **keep theta** (the first choice, the file's own meaning): the arm's home
  pose stays where it is and the home joint value becomes ``theta - offset``;
- **keep the home joint value**: theta becomes ``home + offset``, and the
  arm's home pose turns by the change of offset. This is the Robotics
  Toolbox's reading, where joint value 0 puts theta at the offset.

Either way limits, poses and programs are joint values and keep their
numbers. The entry shows, as the offset is typed, what home becomes.

A joint's type is chosen from a list (enter on its ``type`` cell) or
toggled (``t``). The core's toggle gives the new variable default limits and
no offset or speeds; switching back gets the joint's own back (the whole
robot as it was when nothing changed in between, else the joint's limits
and speeds).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Joint, Robot
from dhsim_tui.tui.screens.dialogs import Choice
from dhsim_tui.tui.screens.editor_table import number
from dhsim_tui.tui.screens.value_entry import ValueEntry

if TYPE_CHECKING:
    from dhsim_tui.tui.screens.editor import EditorScreen

#: the type choice: (value, what the user reads)
TYPE_CHOICES = [
    ("revolute", "revolute (R): it turns, theta is its variable"),
    ("prismatic", "prismatic (P): it slides, d is its variable"),
]
#: how many switches of type the editor remembers, to switch back
RETYPES_KEPT = 64


def _with_joint(robot: Robot, index: int, joint: Joint) -> Robot:
    """``robot`` with joint ``index`` replaced (checked: a DhsimError if not valid)."""
    joints = (*robot.joints[:index], joint, *robot.joints[index + 1 :])
    return replace(robot, joints=joints)


def _names(robot: Robot, index: int) -> tuple[Joint, str, str, str]:
    """(joint, its variable's name, its label such as Th2, its unit)."""
    joint = robot.joints[index]
    return joint, joint.variable, joint.label(index + 1), joint.unit(robot.units)


# -- the D-H variable and the home joint value ---------------------------------
async def edit_variable(screen: EditorScreen, index: int) -> None:
    """Joint ``index``'s D-H variable at home (theta or d); the entry shows
    the home joint value it gives as it is typed."""
    robot = screen.robot
    joint, name, label, unit = _names(robot, index)
    what = f"joint {index + 1} {name}"

    def value(text: str) -> float:
        return editing.parse_number(text, what)

    def check(text: str) -> Robot:
        return editing.set_joint_field(robot, index, name, value(text))

    def live(text: str) -> str:
        home = value(text) - joint.offset
        shift = f" ({name} - offset {number(joint.offset)})" if joint.offset else ""
        return f"home {label} = {number(home)} {unit}{shift}"

    new = await screen.app.push_screen_wait(
        ValueEntry(
            f"{what} ({unit})",
            number(joint.table_value),
            f"the D-H {name} at home, in {unit} · enter sets · escape cancels",
            check,
            live,
        )
    )
    if new is not None:
        moved = new.joints[index]
        screen.push_edit(
            new,
            f"{what} = {number(moved.table_value)} {unit}: home {label} = "
            f"{number(moved.home)} {unit}",
        )


async def edit_home(screen: EditorScreen, index: int) -> None:
    """Joint ``index``'s home joint value; its D-H variable becomes home + offset."""
    robot = screen.robot
    joint, name, label, unit = _names(robot, index)
    what = f"joint {index + 1} home"

    def value(text: str) -> float:
        return editing.parse_number(text, what)

    def check(text: str) -> Robot:
        return _with_joint(robot, index, joint.with_home(value(text)))

    def live(text: str) -> str:
        return f"{name} becomes {number(value(text) + joint.offset)} {unit}"

    new = await screen.app.push_screen_wait(
        ValueEntry(
            f"{what} {label} ({unit})",
            number(joint.home),
            f"the joint value at home, within {number(joint.min)}..{number(joint.max)} "
            f"{unit}; {name} = home + offset",
            check,
            live,
        )
    )
    if new is not None:
        moved = new.joints[index]
        screen.push_edit(
            new,
            f"{what} {label} = {number(moved.home)} {unit}: "
            f"{name} = {number(moved.table_value)} {unit}",
        )


# -- the offset ------------------------------------------------------------------
@dataclass(frozen=True)
class OffsetEdit:
    """What a new offset can make of the robot: theta kept (the home pose
    stays) or the home joint value kept (theta follows); each a robot or
    the reason it cannot be."""

    offset: float
    keep_pose: Robot | DhsimError
    keep_home: Robot | DhsimError


def offset_edits(robot: Robot, index: int, offset: float) -> OffsetEdit:
    """The two robots a new ``offset`` of joint ``index`` can give."""
    joint = robot.joints[index]
    outcomes: list[Robot | DhsimError] = []
    for new_joint in (
        replace(joint, offset=offset),
        replace(joint, offset=offset, **{joint.variable: joint.home + offset}),
    ):
        try:
            outcomes.append(_with_joint(robot, index, new_joint))
        except DhsimError as exc:
            outcomes.append(exc)
    return OffsetEdit(offset, *outcomes)


def offset_live(robot: Robot, index: int, offset: float) -> str:
    """The entry's live line for ``offset``: what home becomes if theta stays,
    and what theta becomes if home stays."""
    joint, name, label, unit = _names(robot, index)
    if offset == joint.offset:
        return f"home {label} stays {number(joint.home)} {unit}"
    becomes = number(joint.table_value - offset)
    return (
        f"home {label} becomes {becomes} {unit} ({name} stays {number(joint.table_value)}), "
        f"or keep home {number(joint.home)}: {name} becomes {number(joint.home + offset)}"
    )


def offset_choices(robot: Robot, index: int, edit: OffsetEdit) -> tuple[list, tuple[str, ...]]:
    """The choice after an offset is typed: (choices, the disabled ones)."""
    joint, name, label, unit = _names(robot, index)
    home_after = number(joint.table_value - edit.offset)
    theta_after = number(joint.home + edit.offset)
    pose = (
        f"keep {name} {number(joint.table_value)}: the home pose stays, "
        f"home {label} becomes {home_after} {unit}"
    )
    home = (
        f"keep home {label} {number(joint.home)} {unit}: {name} becomes {theta_after}, "
        f"the home pose moves"
    )
    choices = []
    disabled = []
    for key, text, outcome in (("pose", pose, edit.keep_pose), ("home", home, edit.keep_home)):
        if isinstance(outcome, DhsimError):
            text = f"{text} (not possible: {_reason(joint, unit, edit.offset, key, outcome)})"
            disabled.append(key)
        choices.append((key, text))
    return choices, tuple(disabled)


def _reason(joint: Joint, unit: str, offset: float, key: str, error: DhsimError) -> str:
    """Why keeping theta (``pose``) or home cannot be, in a few words."""
    home = joint.table_value - offset if key == "pose" else joint.home
    if not joint.min <= home <= joint.max:
        return f"outside its limits {number(joint.min)}..{number(joint.max)} {unit}"
    where, _, why = str(error).partition(": ")
    return why if where.startswith("joints[") and why else str(error)


async def edit_offset(screen: EditorScreen, index: int) -> None:
    """Joint ``index``'s offset: typed (the entry shows what home becomes),
    then the choice of what stays, theta or the home joint value."""
    robot = screen.robot
    joint, name, label, unit = _names(robot, index)
    what = f"joint {index + 1} offset"

    def value(text: str) -> float:
        return editing.parse_number(text, what)

    def check(text: str) -> OffsetEdit:
        edit = offset_edits(robot, index, value(text))
        if isinstance(edit.keep_pose, DhsimError) and isinstance(edit.keep_home, DhsimError):
            raise edit.keep_pose
        return edit

    edit = await screen.app.push_screen_wait(
        ValueEntry(
            f"{what} ({unit})",
            number(joint.offset),
            f"{name} = joint value + offset · enter asks what stays · escape cancels",
            check,
            lambda text: offset_live(robot, index, value(text)),
        )
    )
    if edit is None:
        return
    if edit.offset == joint.offset:
        screen.say(f"{what} stays {number(joint.offset)} {unit}")
        return
    choices, disabled = offset_choices(robot, index, edit)
    answer = await screen.app.push_screen_wait(
        Choice(
            f"{what} {number(joint.offset)} -> {number(edit.offset)} {unit}",
            choices,
            "pose",
            disabled=disabled,
            question=f"home {label} = {name} - offset: which stays?",
        )
    )
    if answer is None:
        screen.say(f"{what} not changed")
        return
    new = edit.keep_pose if answer == "pose" else edit.keep_home
    assert isinstance(new, Robot)  # a disabled choice cannot be picked
    moved = new.joints[index]
    kept = f"{name} kept" if answer == "pose" else f"home {label} kept"
    screen.push_edit(
        new,
        f"{what} = {number(moved.offset)} {unit} ({kept}): {name} = "
        f"{number(moved.table_value)}, home {label} = {number(moved.home)} {unit}",
    )


# -- the type ----------------------------------------------------------------------
@dataclass(frozen=True)
class Retype:
    """One switch of joint ``index``'s type: the robot before and after."""

    index: int
    before: Robot
    after: Robot


def retyped_robot(robot: Robot, index: int, kept: list[Retype]) -> tuple[Robot, bool]:
    """Joint ``index`` switched to the other type: (robot, restored).

    When it had that type before (the last switch of joint ``index`` away
    from it, the joint's a and alpha the same), it gets back what it had:
    the whole robot as it was when nothing changed since that switch (its
    offset, poses and programs too), else its limits and speeds. Otherwise
    the core's toggle: default limits, no offset or speeds. The switch is
    recorded in ``kept`` (the last :data:`RETYPES_KEPT`)."""
    joint = robot.joints[index]
    toggled = editing.toggle_type(robot, index)
    target = toggled.joints[index].type
    new: Robot | None = None
    for retype in reversed(kept):
        old = retype.before.joints[index] if retype.before.dof > index else None
        if (
            retype.index != index
            or retype.after.dof != robot.dof
            or old is None
            or old.type != target
        ):
            continue
        if retype.after == robot:
            new = retype.before
        elif (old.a, old.alpha) == (joint.a, joint.alpha):
            own = replace(
                toggled.joints[index], min=old.min, max=old.max, vmax=old.vmax, amax=old.amax
            )
            try:
                new = _with_joint(toggled, index, own)
            except DhsimError:
                new = None  # its home, a pose or a program is outside them: the defaults
        break
    restored = new is not None
    if new is None:
        new = toggled
    kept.append(Retype(index, robot, new))
    del kept[:-RETYPES_KEPT]
    return new, restored


def switch_type(screen: EditorScreen, index: int) -> None:
    """Joint ``index`` becomes the other type (its limits back if it was that type)."""
    robot = screen.robot
    try:
        new, restored = retyped_robot(robot, index, screen.retyped)
    except DhsimError as exc:
        screen.say(str(exc), error=True)
        return
    joint = new.joints[index]
    unit = joint.unit(new.units)
    limits = f"limits {number(joint.min)}..{number(joint.max)} {unit}"
    if restored:
        message = f"joint {index + 1} is now {joint.type} again, its own {limits} back"
    else:
        message = f"joint {index + 1} is now {joint.type} ({limits})"
    screen.push_edit(new, message)


async def choose_type(screen: EditorScreen, index: int) -> None:
    """Enter on the type cell: revolute or prismatic, from a list."""
    joint = screen.robot.joints[index]
    answer = await screen.app.push_screen_wait(
        Choice(f"joint {index + 1} type", TYPE_CHOICES, joint.type)
    )
    if answer is None:
        return
    if answer == screen.robot.joints[index].type:
        screen.say(f"joint {index + 1} stays {answer}")
        return
    switch_type(screen, index)
