"""The app as a snapshot test loads it: the bundled Puma 560 at home."""

from dhsim_tui.app import DhsimApp
from dhsim_tui.core import load_robot

robot, path = load_robot("puma560")
app = DhsimApp(robot, path, animate=False)  # moves land at once: deterministic

if __name__ == "__main__":
    app.run()
