"""The Textual application: holds the running robot and moves between screens."""

from __future__ import annotations

from pathlib import Path

from textual import work
from textual.app import App

from dhsim_tui.core import editing
from dhsim_tui.core.model import MAX_JOINTS, Robot
from dhsim_tui.core.robotfile import save
from dhsim_tui.screens.control import ControlScreen
from dhsim_tui.screens.editor import EditorScreen, is_bundled
from dhsim_tui.screens.value_entry import ValueEntry


def _joint_count(text: str) -> int:
    value = editing.parse_number(text, "joints")
    if value != int(value) or not 1 <= value <= MAX_JOINTS:
        raise editing.DhsimError(f"joints: a whole number from 1 to {MAX_JOINTS}")
    return int(value)


class DhsimApp(App):
    """dhsim's terminal UI. Everything is reachable from the keyboard.

    ``start`` is ``"control"`` (the simulator), ``"edit"`` (the editor on
    ``robot``) or ``"new"`` (ask for a joint count, then the editor).
    """

    CSS_PATH = "dhsim.tcss"
    TITLE = "dhsim"
    ENABLE_COMMAND_PALETTE = False

    def __init__(
        self,
        robot: Robot,
        path: Path | None = None,
        renderer: str = "braille",
        start: str = "control",
        animate: bool = True,
    ) -> None:
        super().__init__()
        self.animate = animate
        self.robot = robot
        self.robot_path = path
        #: the robot as its file holds it (a pose saved only in memory differs)
        self.saved_robot: Robot | None = robot if path is not None else None
        self.renderer = renderer
        self.start = start
        self.sub_title = robot.name

    def on_mount(self) -> None:
        # pushed (not the default screen) so that switch_screen can replace it
        self.push_screen(ControlScreen(self.robot, self.renderer, self.animate))
        if self.start == "edit":
            self.open_editor(self.robot, self.robot_path, saved=self.saved_robot)
        elif self.start == "new":
            self.start_new_robot()

    @work(exclusive=True, group="modal")
    async def start_new_robot(self) -> None:
        """The seed's guided start: how many joints? Then everything in the table."""
        count = await self.push_screen_wait(
            ValueEntry(
                "new robot: number of joints",
                "3",
                f"1 to {MAX_JOINTS} revolute rows; escape starts with 1",
                _joint_count,
            )
        )
        self.open_editor(editing.new_robot(self.robot.name, count or 1), None, saved=None)

    def open_editor(self, robot: Robot, path: Path | None, saved: Robot | None = None) -> None:
        """The editor on ``robot``; ``saved`` is what its file holds (changes
        against it count as unsaved)."""
        editor = EditorScreen(robot, path, self.renderer, saved=saved)
        self.push_screen(editor, self._editor_closed)

    def action_edit(self) -> None:
        self.open_editor(self.robot, self.robot_path, saved=self.saved_robot)

    def _editor_closed(self, result: tuple[Robot, Path | None] | None) -> None:
        """After the editor: the simulator runs the saved robot."""
        if result is None:
            return
        robot, path = result
        self.saved_robot = robot
        if (robot, path) != (self.robot, self.robot_path):
            self.robot, self.robot_path = robot, path
            self.sub_title = robot.name
            self.switch_screen(ControlScreen(robot, self.renderer, self.animate))

    def keep_robot(self, robot: Robot) -> Path | None:
        """The simulator changed the robot (a saved pose): keep it, and write it
        to its file when it has one of its own (bundled robots are templates).
        A failed save raises DhsimError; the robot is kept in memory either way."""
        self.robot = robot
        path = self.robot_path
        if path is None or is_bundled(path):
            return None
        save(robot, path)
        self.saved_robot = robot
        return path

    async def action_quit(self) -> None:
        """Quit, unless an editor anywhere on the stack has unsaved changes:
        then ask (a dialog on top of the editor must not let them slip)."""
        for screen in reversed(self.screen_stack):
            if isinstance(screen, EditorScreen) and screen.dirty:
                self._quit_with_guard(screen)
                return
        self.exit()

    @work(exclusive=True, group="modal")
    async def _quit_with_guard(self, editor: EditorScreen) -> None:
        if await editor.guard("quitting"):
            self.exit()


def run_app(
    robot: Robot, path: Path | None = None, renderer: str = "braille", start: str = "control"
) -> int:
    DhsimApp(robot, path, renderer, start).run()
    return 0
