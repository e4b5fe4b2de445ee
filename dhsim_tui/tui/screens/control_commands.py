"""The simulator's commands in the palette (ctrl+p): each calls an action the
screen or the app already has."""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from dhsim_tui.core.model.validation import fmt
from dhsim_tui.core.motion.jog import TOOL, WORLD
from dhsim_tui.scene.wireframe import FRAME_MODE_NAMES, FRAME_MODES
from dhsim_tui.tui.screens.palette_command import VIEW_NAMES, PaletteCommand
from dhsim_tui.tui.widgets.cartesian_panel import CartesianPanel
from dhsim_tui.tui.widgets.views_panel import ViewsPanel

if TYPE_CHECKING:
    from dhsim_tui.tui.screens.control import ControlScreen


def control_commands(app, screen: ControlScreen) -> Iterator[PaletteCommand]:
    robot = app.robot
    yield PaletteCommand(
        "Open a robot…",
        "a robot file, or a .urdf or .csv to import; the simulator runs it",
        app.open_robot,
    )
    yield PaletteCommand(
        "Import a URDF or CSV file…",
        "the simulator runs the robot it gives (not saved until you save it)",
        lambda: app.open_robot(importing=True),
    )
    if app.has_unsaved_poses:
        what = "the poses kept in memory" if app.robot_path is not None else "this robot"
        yield PaletteCommand("Save", f"save {what} (asks a name when it has no file)", app.save)
    yield PaletteCommand(
        "Save as…", "save the robot under another name, robots/<name>.toml", app.save_as
    )
    yield PaletteCommand("Export…", "write the robot as URDF, CSV or JSON", app.export_robot)
    other = "modified" if robot.convention == "standard" else "standard"
    yield PaletteCommand(
        f"Convert to {other} D-H",
        "the same arm: opens the editor with the change (ctrl+z there undoes it)",
        lambda: app.convert_in_editor(other),
    )
    yield PaletteCommand("Edit the D-H table", "the table editor (e)", screen.action_edit)
    yield PaletteCommand(
        "Go home",
        "every joint home: the D-H table's values less the offsets (h)",
        screen.action_home,
    )
    for name in robot.pose_names:
        values = ", ".join(fmt(v) for v in robot.pose(name))
        yield PaletteCommand(
            f"Go to pose {name}",
            f"joints {values}",
            lambda name=name: screen.go_to_pose(name),
        )
    views = screen.query_one(ViewsPanel)
    for index, view in enumerate(VIEW_NAMES):
        yield PaletteCommand(
            f"View: {view}",
            f"select the {view} view ({index + 1})",
            lambda index=index: views.action_view(index),
        )
    if views.maximised:
        yield PaletteCommand("View: restore", "all the panels back (z)", views.action_maximise)
    else:
        yield PaletteCommand(
            "View: maximise", "the selected view over the whole screen (z)", views.action_maximise
        )
    if views.zoom != 1.0:
        yield PaletteCommand(
            "View: reset zoom",
            "back to the whole work area (0)",
            lambda: views.action_zoom(0),
        )
    if views.fit:
        yield PaletteCommand(
            "View: the work area", "every view back to the work area (F)", views.action_fit
        )
    else:
        yield PaletteCommand(
            "View: fit the arm", "every view fitted to the arm as it stands (F)", views.action_fit
        )
    following = FRAME_MODES[(FRAME_MODES.index(views.frames) + 1) % len(FRAME_MODES)]
    yield PaletteCommand(
        f"View: frames drawn: {FRAME_MODE_NAMES[following]}",
        f"the frame axes drawn: now {FRAME_MODE_NAMES[views.frames]} (x)",
        views.action_frames,
    )
    if screen.cloud_state == "off":
        yield PaletteCommand(
            "View: show the workspace",
            "a faint cloud of points the tool can reach, in every view (W)",
            screen.action_workspace,
        )
    else:
        yield PaletteCommand(
            "View: hide the workspace", "the workspace cloud off (W)", screen.action_workspace
        )
    yield PaletteCommand(
        "Next IK branch",
        "the arm's next solution for this tool pose: the tool stays (b)",
        screen.action_next_branch,
    )
    frame = TOOL if screen.query_one(CartesianPanel).frame == WORLD else WORLD
    yield PaletteCommand(
        f"Jog in the {frame} frame",
        (
            "Cartesian jogging along and about the tool's own x, y, z (f)"
            if frame == TOOL
            else "Cartesian jogging along and about the world's X, Y, Z (f)"
        ),
        lambda frame=frame: _jog_in(screen, frame),
    )
    yield PaletteCommand("Help", "every key of the simulator (?)", screen.action_help)


def _jog_in(screen: ControlScreen, frame: str) -> None:
    """Cartesian jogging (switched on if it is off) in ``frame``."""
    if not screen.cartesian:
        screen.action_switch("cartesian")
    screen.query_one(CartesianPanel).action_frame(frame)
