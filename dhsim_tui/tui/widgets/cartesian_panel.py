"""The Cartesian panel: the tool's pose, one row per direction it can be jogged.

The title names the jogging frame (``f`` switches it). In the WORLD frame the
rows move the tool along the world's X, Y, Z and turn it about the world's
axes through the tool point; each shows a current value, as a teach pendant
does: the tool's world X, Y, Z and its orientation as roll, pitch and yaw. In
the TOOL frame the rows move along and turn about the tool's own x, y, z: the
position rows show which way each tool axis points in the world (z is the
approach vector), the turn rows roll, pitch and yaw.

It takes focus: while it has it, the arrows pick a row and move the tool,
``[ ]`` change the step, enter asks for a target and ``f`` switches the frame.
The panel keeps the row and the frame; the moves it posts as messages, and
the screen answers them (inverse kinematics is the core's) and hands the
pose back with :meth:`CartesianPanel.show`.

Few bytes per key press (``bench/bytes.py`` counts them): one styled run
per row, and a new pose repaints only the rows that changed, each up to its
last changed column.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from rich.text import Text
from textual import events
from textual.binding import Binding
from textual.message import Message
from textual.reactive import reactive

from dhsim_tui.core.model.robot import LENGTH_DECIMALS
from dhsim_tui.core.motion.jog import CARTESIAN_ROWS, TOOL, WORLD
from dhsim_tui.tui.keys import Keys
from dhsim_tui.tui.widgets.joint_row import ascii_mode
from dhsim_tui.tui.widgets.pose_panel import TextPanel, refresh_changed_lines
from dhsim_tui.tui.widgets.stepping import (
    STEP_SIZE_BINDINGS,
    StepSizeRequested,
    arrow_bindings,
)

#: the panel's title in each jogging frame (f switches)
TITLES = {WORLD: "Cartesian: WORLD frame (f)", TOOL: "Cartesian: TOOL frame (f)"}
TITLE = TITLES[WORLD]
#: the angle shown on each turn row
ANGLES = {"Rx": "roll", "Ry": "pitch", "Rz": "yaw"}


def cartesian_text(
    xyz: tuple[float, float, float],
    rpy: tuple[float, float, float],
    selected: int,
    units: str,
    ascii: bool = False,
    frame: str = WORLD,
    axes: Sequence[Sequence[float]] | None = None,
) -> Text:
    """Six rows, the selected one marked ``▶`` (ASCII ``>``); fixed columns so
    values don't jitter. ``axes``: the tool's x, y, z axes in world
    coordinates (the rotation's columns), shown on the TOOL frame's rows."""
    text = Text()
    places = LENGTH_DECIMALS[units]
    pointer, degree = (">", "deg") if ascii else ("▶", "°")
    tool = frame == TOOL and axes is not None
    for i, name in enumerate(CARTESIAN_ROWS):
        marker = pointer if i == selected else " "
        style = "bold reverse" if i == selected else ""
        if i < 3 and tool:
            x, y, z = (round(float(v), 2) + 0.0 for v in axes[i])
            line = f"{marker} {name.lower():<3}tool {name.lower()} = ({x:5.2f},{y:5.2f},{z:5.2f})"
        elif i < 3:
            value = f"{round(xyz[i], places) + 0.0:11.{places}f}"
            line = f"{marker} {name:<3}{'world':<12}{value} {units}"
        else:
            axis = f"tool {name[1]}" if frame == TOOL else f"world {name[1].upper()}"
            value = f"{round(rpy[i - 3], 2) + 0.0:10.2f}"
            line = f"{marker} {name:<3}{axis:<8}{ANGLES[name]:<5}{value}{degree}"
        text.append(line, style=style)
        if i < len(CARTESIAN_ROWS) - 1:
            text.append("\n")
    return text


SELECT = Keys("axis", help="select an axis: X, Y, Z or a turn about x, y, z")
MOVE = Keys("move the tool (shift ×10)", help="move the tool along the axis, or turn it about it")
BIG_MOVE = Keys(legend=False, help="ten steps at once")
ENTER = Keys("target", help="type a target for the selected axis")
FRAME = Keys(
    "world/tool frame",
    help="Cartesian: along/about the world's X, Y, Z ⇄ the tool's own x, y, z (TOOL)",
)

BINDINGS = [
    *arrow_bindings("cartesian", "row", "jog", "Axis", "Move tool", (SELECT, MOVE, BIG_MOVE)),
    *STEP_SIZE_BINDINGS,
    Binding("enter", "ask_target", "Set", key_display="⏎", show=False, id="cartesian.enter",
            tooltip="Type a target for the selected axis", group=ENTER),
    # f's label names the frame it switches to
    Binding("f", "frame('tool')", "Tool frame", show=False, id="cartesian.tool_frame",
            tooltip="Jog in the TOOL frame: along and about the tool's own x, y, z", group=FRAME),
    Binding("f", "frame('world')", "World frame", show=False, id="cartesian.world_frame",
            tooltip="Jog in the WORLD frame: along and about the world's X, Y, Z", group=FRAME),
]  # fmt: skip


class CartesianPanel(TextPanel, can_focus=True):
    """The tool's pose as the screen hands it, the selected row and the frame."""

    DEFAULT_CSS = "CartesianPanel { height: 8; }"
    ALLOW_SELECT = False
    BINDINGS = BINDINGS

    #: the selected row (CARTESIAN_ROWS) and the frame jogged in
    row: reactive[int] = reactive(0, init=False)
    frame: reactive[str] = reactive(WORLD, init=False)

    @dataclass
    class RowSelected(Message):
        """Another row was selected (a key or a click)."""

        row: int

    @dataclass
    class JogRequested(Message):
        """Move the tool ``steps`` steps along (or about) ``row`` in ``frame``."""

        row: int
        steps: int
        frame: str

    @dataclass
    class TargetAsked(Message):
        """Enter: ask for a target for ``row`` in ``frame``."""

        row: int
        frame: str

    @dataclass
    class FrameChanged(Message):
        """``f``: jogging is now in ``frame``."""

        frame: str

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self._pose: tuple | None = None  # what show() was last handed
        self.border_title = TITLES[self.frame]

    # -- keys --------------------------------------------------------------------
    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        if action == "frame":  # one key, two labels: the frame f switches to
            return bool(parameters) and parameters[0] != self.frame
        return True

    def action_row(self, delta: int) -> None:
        self.row = (self.row + delta) % len(CARTESIAN_ROWS)

    def action_jog(self, steps: int) -> None:
        self.post_message(self.JogRequested(self.row, steps, self.frame))

    def action_step_size(self, delta: int) -> None:
        self.post_message(StepSizeRequested(delta))

    def action_ask_target(self) -> None:
        self.post_message(self.TargetAsked(self.row, self.frame))

    def action_frame(self, frame: str = "") -> None:
        """The world's axes or the tool's own (``frame``: the one to switch
        to; the other one, when not given)."""
        self.frame = frame if frame in (WORLD, TOOL) else (TOOL if self.frame == WORLD else WORLD)

    def watch_row(self, row: int) -> None:
        self._show_again()
        self.post_message(self.RowSelected(row))

    def watch_frame(self, frame: str) -> None:
        self.border_title = TITLES[frame]  # a border title repaints the whole panel
        self.refresh_bindings()
        self.post_message(self.FrameChanged(frame))

    def _on_hide(self, event: events.Hide) -> None:
        """Hidden (a maximised view, a terminal too small), it keeps the focus:
        its keys go on working, and come back with it (Textual's own would
        hand the focus on)."""
        event.prevent_default()

    # -- the mouse ---------------------------------------------------------------
    def _row_at(self, y: int) -> int | None:
        return y if 0 <= y < len(CARTESIAN_ROWS) else None

    def on_click(self, event: events.Click) -> None:
        """A click on a row selects it (and Cartesian jogging)."""
        row = self._row_at(event.y)
        if row is not None:
            self.focus()
            self.row = row

    def on_mouse_scroll_up(self, event: events.MouseScrollUp) -> None:
        self._wheel(event, 1)

    def on_mouse_scroll_down(self, event: events.MouseScrollDown) -> None:
        self._wheel(event, -1)

    def _wheel(self, event: events.MouseEvent, steps: int) -> None:
        """The wheel over a row moves the tool that many steps along it."""
        event.stop()
        row = self._row_at(event.y)
        if row is not None:
            self.focus()
            self.row = row
            self.post_message(self.JogRequested(row, steps, self.frame))

    # -- what the screen hands it --------------------------------------------------
    def show(
        self,
        xyz: tuple[float, float, float],
        rpy: tuple[float, float, float],
        units: str,
        axes: Sequence[Sequence[float]] | None = None,
    ) -> None:
        """The tool's position, roll-pitch-yaw and (TOOL frame) its axes."""
        self._pose = (xyz, rpy, units, axes)
        text = cartesian_text(xyz, rpy, self.row, units, ascii_mode(self), self.frame, axes)
        refresh_changed_lines(self, self._text, text)
        self._text = text

    def _show_again(self) -> None:
        if self._pose is not None:
            self.show(*self._pose)
