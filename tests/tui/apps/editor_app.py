"""The editor as a snapshot test loads it: the bundled Puma 560."""

from rich.color import ColorSystem

from dhsim_tui.core import load_robot
from dhsim_tui.tui.app import DhsimApp

robot, path = load_robot("puma560")
app = DhsimApp(robot, path, start="edit", animate=False)
# the same pictures whatever TERM the tests run under: a truecolor terminal
app.console._color_system = ColorSystem.TRUECOLOR

if __name__ == "__main__":
    app.run()
