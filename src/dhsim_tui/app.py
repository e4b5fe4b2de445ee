"""The Textual application: holds the robot, shows the control screen."""

from __future__ import annotations

from pathlib import Path

from textual.app import App

from dhsim_tui.core.model import Robot
from dhsim_tui.screens.control import ControlScreen


class DhsimApp(App):
    """dhsim's terminal UI. Everything is reachable from the keyboard."""

    CSS_PATH = "dhsim.tcss"
    TITLE = "dhsim"
    ENABLE_COMMAND_PALETTE = False

    def __init__(self, robot: Robot, path: Path | None = None, renderer: str = "braille") -> None:
        super().__init__()
        self.robot = robot
        self.robot_path = path
        self.renderer = renderer
        self.sub_title = robot.name

    def get_default_screen(self) -> ControlScreen:
        return ControlScreen(self.robot, self.renderer)


def run_app(robot: Robot, path: Path | None = None, renderer: str = "braille") -> int:
    DhsimApp(robot, path, renderer).run()
    return 0
