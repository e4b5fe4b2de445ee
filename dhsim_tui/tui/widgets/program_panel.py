"""The program panel: a program's steps, the one selected, and playback.

It takes focus (``g`` on the simulator, or a click): while it has it, the
arrows select a step, ``l`` makes the step a joint or a linear move,
``delete`` removes it, ``ctrl+↑ ↓`` move it, ``ctrl+z`` undoes, ``,`` and
``.`` go a step back or on, ``n`` to the next problem. Each is a message to
the screen, which holds the program (in the robot) and plays it; the panel
shows what it is handed: the steps, the time, the problems.
"""

from __future__ import annotations

from dataclasses import dataclass

from rich.text import Text
from textual import events
from textual.binding import Binding
from textual.message import Message
from textual.reactive import reactive

from dhsim_tui.core.model.program import Program
from dhsim_tui.tui.keys import Keys
from dhsim_tui.tui.widgets.joint_row import ascii_mode
from dhsim_tui.tui.widgets.pose_panel import TextPanel, refresh_changed_lines

SELECT = Keys("step", help="select a step of the program")
KIND = Keys("joint/linear", help="the selected step: a joint move ⇄ a linear move")
DELETE = Keys("delete step", help="delete the selected step")
MOVE = Keys("move step", help="move the selected step up / down")
UNDO = Keys("undo", help="undo the last change to the program")
SEEK = Keys("step back/on", help="playback: to the start of the step before / after")
PLOT = Keys("plot", help="the joints and the tool speed against time, at the time played")
SPEED = Keys("play speed", help="playback slower / faster: ×¼ ×½ ×1 ×2 ×4")
PROBLEM = Keys("next problem", help="playback: to the next problem the path check found")
INSERT = Keys("insert step", help="the current pose as a step after the selected one")
WAIT = Keys("add wait", help="a wait after the selected step (asks the seconds)")
STEP_SPEED = Keys("speed", help="the selected step's speed (a wait: its seconds)")
TARGET = Keys("edit step", help="the selected step's target: joint values, or the tool pose")
RENAME = Keys("rename", help="rename the program")
NEW = Keys("new program", help="start a new, empty program")
OTHER = Keys("other program", help="show the next of the robot's programs")

BINDINGS = [
    Binding("up", "select(-1)", "Step", key_display="↑↓", id="program.prev",
            tooltip="Select the previous step", group=SELECT),
    Binding("down", "select(1)", "Step", show=False, id="program.next",
            tooltip="Select the next step", group=SELECT),
    Binding("l", "change('kind')", "Joint/linear", show=False, id="program.kind",
            tooltip="Make the selected step a linear move, or a joint move", group=KIND),
    Binding("delete,backspace", "change('delete')", "Delete", show=False, id="program.delete",
            tooltip="Delete the selected step", group=DELETE),
    Binding("ctrl+up", "change('up')", "Move up", show=False, id="program.move_up",
            tooltip="Move the selected step up", group=MOVE),
    Binding("ctrl+down", "change('down')", "Move down", show=False, id="program.move_down",
            tooltip="Move the selected step down", group=MOVE),
    Binding("ctrl+z", "change('undo')", "Undo", show=False, id="program.undo",
            tooltip="Undo the last change to the program", group=UNDO),
    Binding("I", "change('insert')", "Insert", show=False, id="program.insert",
            tooltip="Record the current pose after the selected step", group=INSERT),
    Binding("D", "change('wait')", "Wait", show=False, id="program.wait",
            tooltip="Add a wait (a delay) after the selected step", group=WAIT),
    Binding("S", "change('speed')", "Speed", show=False, id="program.speed",
            tooltip="Set the selected step's speed, or a wait's seconds", group=STEP_SPEED),
    Binding("enter", "change('target')", "Edit", show=False, id="program.target",
            tooltip="Edit the selected step's target numbers", group=TARGET),
    Binding("r", "change('rename')", "Rename", show=False, id="program.rename",
            tooltip="Rename the program", group=RENAME),
    Binding("N", "change('new')", "New", show=False, id="program.new",
            tooltip="Start a new program", group=NEW),
    Binding("o", "change('next_program')", "Other", show=False, id="program.other",
            tooltip="Show the robot's next program", group=OTHER),
    Binding("comma", "seek(-1)", "Back", show=False, id="program.back",
            tooltip="To the start of the step before", group=SEEK),
    Binding("full_stop", "seek(1)", "On", show=False, id="program.on",
            tooltip="To the start of the next step", group=SEEK),
    Binding("n", "next_problem", "Next problem", show=False, id="program.problem",
            tooltip="To the next problem the path check found", group=PROBLEM),
    Binding("t", "plot", "Plot", show=False, id="program.plot",
            tooltip="The joints and the tool speed against time", group=PLOT),
    Binding("left_square_bracket", "speed(-1)", "Slower", show=False, id="program.slower",
            tooltip="Play slower", group=SPEED),
    Binding("right_square_bracket", "speed(1)", "Faster", show=False, id="program.faster",
            tooltip="Play faster", group=SPEED),
]  # fmt: skip


#: a step's line is cut to this many columns (the side panel's width)
LINE_WIDTH = 34
#: the most steps shown at once (the rest scroll with the selection)
VISIBLE_STEPS = 10


def window(count: int, selected: int, top: int, visible: int) -> int:
    """The first step shown (0-based) so that ``selected`` is among the
    ``visible`` shown from ``top`` on, moving as little as it can."""
    if count <= visible:
        return 0
    top = min(top, selected)
    top = max(top, selected - visible + 1)
    return min(max(top, 0), count - visible)


def step_range(count: int, top: int, visible: int) -> str:
    """``3–12 of 20``, or ``""`` when every step is shown."""
    if count <= visible:
        return ""
    return f"{top + 1}–{min(top + visible, count)} of {count}"


def program_text(
    program: Program | None,
    selected: int,
    playing_step: int | None,
    marks: dict[int, int],
    ascii: bool = False,
    top: int = 0,
    visible: int | None = None,
    width: int = LINE_WIDTH,
) -> Text:
    """One line per step shown (``visible`` from ``top`` on; all when None),
    the selected one marked ``▶``, the one playing ``•``; ``marks``:
    problems per step (1-based)."""
    text = Text()
    if program is None or not program.steps:
        text.append("no steps yet: R records the current pose", style="dim")
        return text
    pointer, playing = (">", "*") if ascii else ("▶", "•")
    last = len(program.steps) if visible is None else top + visible
    for index, step in enumerate(program.steps[top:last], start=top):
        number = index + 1
        marker = pointer if index == selected else " "
        now = playing if playing_step == number else " "
        line = f"{marker}{now}{number:>3} {step.describe()}"
        problems = marks.get(number, 0)
        room = width - (len(f"  !{problems}") if problems else 0)  # the mark always shows
        if len(line) > room:
            line = line[: room - 1] + ("~" if ascii else "…")
        style = "bold reverse" if index == selected else ""
        if index > top:
            text.append("\n")
        text.append(line, style=style)
        if problems:
            text.append(f"  !{problems}", style="bold red")
    return text


class ProgramPanel(TextPanel, can_focus=True):
    """Shows the program it is handed; its keys ask the screen."""

    DEFAULT_CSS = "ProgramPanel { height: auto; max-height: 12; }"
    ALLOW_SELECT = False
    BINDINGS = BINDINGS

    selected: reactive[int] = reactive(0, init=False)
    #: what R records, shown in the title: "joint" or "linear"
    record_move: reactive[str] = reactive("joint", init=False)

    @dataclass
    class Changed(Message):
        """A change asked of the selected step: ``kind``, ``delete``, ``up``,
        ``down`` or ``undo``."""

        change: str
        index: int

    @dataclass
    class Seek(Message):
        """Playback to the start of the step ``steps`` before (< 0) or after."""

        steps: int

    class NextProblem(Message):
        """Playback to the next problem."""

    class PlotAsked(Message):
        """``t``: the program's plot."""

    @dataclass
    class SpeedAsked(Message):
        """``[`` or ``]``: play slower (-1) or faster (1)."""

        delta: int

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self._shown: tuple = (None, None, {})
        self._top = 0  # the first step shown

    @property
    def visible(self) -> int:
        """How many steps fit: the panel's inner height once laid out (its
        max-height follows the screen's), at most :data:`VISIBLE_STEPS`."""
        inner = self.size.height or VISIBLE_STEPS  # (the size inside the border)
        return max(1, min(VISIBLE_STEPS, inner))

    def show(self, program: Program | None, playing_step: int | None = None, marks=None) -> None:
        """The program's steps, the one playing (1-based) and the problems per step."""
        count = len(program.steps) if program is not None else 0
        if count and self.selected >= count:
            self.set_reactive(ProgramPanel.selected, count - 1)
        self._shown = (program, playing_step, dict(marks or {}))
        self._title()
        self._render_now()

    def _title(self) -> None:
        program = self._shown[0]
        name = f"Program {program.name}" if program is not None else "Program"
        count = len(program.steps) if program is not None else 0
        shown = step_range(count, self._top, self.visible)
        self.border_title = f"{name} · {shown}" if shown else f"{name} · R {self.record_move}"

    def watch_record_move(self) -> None:
        self._title()

    def _render_now(self) -> None:
        program, playing_step, marks = self._shown
        count = len(program.steps) if program is not None else 0
        follow = playing_step - 1 if playing_step else self.selected  # the step playing, or
        top = window(count, follow, self._top, self.visible)  # the one selected, in sight
        if top != self._top:
            self._top = top
            self._title()
        width = max(LINE_WIDTH, self.size.width)  # (inside the border)
        text = program_text(
            program, self.selected, playing_step, marks, ascii_mode(self), top, self.visible, width
        )
        refresh_changed_lines(self, self._text, text)
        self._text = text

    def watch_selected(self) -> None:
        self._render_now()

    def on_resize(self) -> None:
        self._render_now()
        self._title()

    def action_select(self, delta: int) -> None:
        program = self._shown[0]
        if program is not None and program.steps:
            self.selected = (self.selected + delta) % len(program.steps)

    def action_change(self, change: str) -> None:
        self.post_message(self.Changed(change, self.selected))

    def action_seek(self, steps: int) -> None:
        self.post_message(self.Seek(steps))

    def action_next_problem(self) -> None:
        self.post_message(self.NextProblem())

    def action_plot(self) -> None:
        self.post_message(self.PlotAsked())

    def action_speed(self, delta: int) -> None:
        self.post_message(self.SpeedAsked(delta))

    def on_click(self, event: events.Click) -> None:
        """A click on a step selects it."""
        program = self._shown[0]
        self.focus()
        inside = event.get_content_offset(self)  # inside the border (None: on it)
        if program is None or inside is None:
            return
        index = self._top + inside.y
        if 0 <= inside.y < self.visible and index < len(program.steps):
            self.selected = index

    def _on_hide(self, event: events.Hide) -> None:
        """Hidden (a maximised view), it keeps the focus, as the jogging panels do."""
        event.prevent_default()
