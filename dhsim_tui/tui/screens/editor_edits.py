"""The editor's edits of its tables, as plain functions of the editor screen:
a joint's value or a robot field typed in, a joint's type toggled, a joint or
a pose added or deleted (a deletion asks first), a joint moved, the robot
converted to the other D-H convention, an edit undone or redone. Each goes
through :mod:`dhsim_tui.core.model.editing` by way of the screen's
``attempt`` or ``push_edit``: a rejected edit is shown where it was made and
changes nothing, an accepted one goes on the undo history with a message
saying what changed. The async ones are awaited from the screen's ``@work``
workers (they wait for answers with ``push_screen_wait``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.tui.flows.fields import ask_field, ask_joint_field, ask_new_pose_name
from dhsim_tui.tui.screens.dialogs import Confirm
from dhsim_tui.tui.screens.editor_changes import describe_change
from dhsim_tui.tui.screens.editor_joint_values import (
    choose_type,
    edit_home,
    edit_offset,
    edit_variable,
    switch_type,
)

if TYPE_CHECKING:
    from dhsim_tui.tui.screens.editor import EditorScreen


async def edit_joint_value(screen: EditorScreen, index: int, name: str) -> None:
    """Ask for joint ``index``'s ``name`` (a column of the joints table) and
    set it: its type from a list; its D-H variable, offset and home joint
    value showing what home becomes (:mod:`editor_joint_values`)."""
    joint = screen.robot.joints[index]
    if name == "type":
        await choose_type(screen, index)
        return
    if name == joint.variable:
        await edit_variable(screen, index)
        return
    if name == "offset":
        await edit_offset(screen, index)
        return
    if name == "home":
        await edit_home(screen, index)
        return
    answer = await ask_joint_field(screen.app, screen.robot, index, name)
    if answer is not None:
        screen.push_edit(*answer)


async def edit_robot_field(screen: EditorScreen, key: str) -> None:
    """Ask for the robot field ``key`` (a pose: ``pose:<name>``) and set it."""
    try:
        new = await ask_field(screen.app, screen.robot, key)
    except DhsimError as exc:
        screen.say(str(exc), error=True)
        return
    if new is not None:
        screen.push_edit(new, describe_change(screen.robot, new))


def toggle_type(screen: EditorScreen) -> None:
    """The joint under the cursor becomes prismatic, or revolute (switched
    back, with its own limits again: :mod:`editor_joint_values`)."""
    switch_type(screen, screen.joint_index())


async def add_here(screen: EditorScreen) -> None:
    """A joint after the one under the cursor, or (in the robot's fields) a
    pose at the home values, under a name asked for."""
    if screen.in_joints():
        index = screen.joint_index()
        screen.attempt(
            lambda: editing.insert_joint(screen.robot, index),
            f"joint {index + 2} added",
            cursor_row=index + 1,
        )
        return
    name = await ask_new_pose_name(screen.app, screen.robot)
    if name is not None and screen.attempt(
        lambda: editing.set_pose(screen.robot, name, screen.robot.home),
        f"pose {name} added (home values; enter on it edits them)",
    ):
        screen.field_cursor = f"pose:{name}"  # the cursor goes to the new pose


async def delete_here(screen: EditorScreen) -> None:
    """Delete the joint or the pose under the cursor, once confirmed."""
    if screen.in_joints():
        index = screen.joint_index()
        if screen.robot.dof <= 1:
            screen.say("a robot needs at least 1 joint", error=True)
            return
        if await screen.app.push_screen_wait(Confirm(f"Delete joint {index + 1}?")):
            screen.attempt(
                lambda: editing.delete_joint(screen.robot, index), f"joint {index + 1} deleted"
            )
        return
    key = screen.field_key()
    if not key.startswith("pose:"):
        screen.say("only joints and poses can be deleted", error=True)
        return
    name = key.removeprefix("pose:")
    if await screen.app.push_screen_wait(Confirm(f"Delete pose {name}?")):
        screen.attempt(lambda: editing.delete_pose(screen.robot, name), f"pose {name} deleted")


def move_joint(screen: EditorScreen, delta: int) -> None:
    """The joint under the cursor moves ``delta`` rows (up: -1), the cursor with it."""
    index = screen.joint_index()
    screen.attempt(
        lambda: editing.move_joint(screen.robot, index, delta),
        f"joint {index + 1} moved to {index + 1 + delta}",
        cursor_row=index + delta,
    )


def convert_robot(screen: EditorScreen, convention: str) -> None:
    """The same arm in the ``convention`` D-H convention (the core's exact
    conversion: the tool's pose is unchanged at every joint value): one
    edit, which undo reverts."""
    from dhsim_tui.core.interop.convert import convert  # loaded when first used

    before = screen.robot.convention
    screen.attempt(
        lambda: convert(screen.robot, convention),
        f"converted from {before} to {convention} D-H: the same arm (ctrl+z undoes)",
    )


def undo_redo(screen: EditorScreen, undo: bool) -> None:
    """Undo the last edit (``undo``), or redo the last one undone; say which."""
    before = screen.robot
    if screen.history.undo() if undo else screen.history.redo():
        screen.refresh_robot()
        done = "undid" if undo else "redid"
        screen.say(f"{done}: {describe_change(before, screen.robot)}")
    else:
        screen.say(f"nothing to {'undo' if undo else 'redo'}", error=True)
