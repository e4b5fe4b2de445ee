"""Regenerate the README's screenshots from the real app (headless).

    python screenshots/generate.py [PREFIX ...]

Each shot is (file name, robot, terminal size, keys pressed first). With
prefixes, only the shots whose names start with one of them (``control
cartesian`` redraws the simulator's shots and leaves the editor's alone).
"""

from __future__ import annotations

import asyncio
import os
import sys
from pathlib import Path

from rich.color import ColorSystem

from dhsim_tui.core import load_robot
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screenshot import export_svg

HERE = Path(__file__).resolve().parent

#: Th2 to 45, Th3 to -45, Th5 to 30 in 15-degree steps
MOVE = (
    "down",
    "right_square_bracket",
    "right_square_bracket",
    "right",
    "right",
    "right",
    "down",
    "left",
    "left",
    "left",
    "down",
    "down",
    "right",
    "right",
)

#: the view modes' shots: the same moved Puma in each way a terminal can ask for
VIEW_MODES: dict[str, dict] = {
    "views-120x36": {"color_system": "truecolor"},
    "views-16-colours-120x36": {"color_system": "standard"},
    "views-256-colours-120x36": {"color_system": "256"},
    "views-no-color-120x36": {"no_color": True},
    "views-ascii-120x36": {"ascii": True},
    "views-ansi-theme-120x36": {"theme": "ansi"},
}

SHOTS: list[tuple[str, str, tuple[int, int], tuple[str, ...]]] = [
    *[(name, "puma560", (120, 36), MOVE) for name in VIEW_MODES],
    ("views-work-area-120x36", "puma560", (120, 36), (*MOVE, "F")),  # F: out of the fit
    ("views-3d-maximised-120x36", "puma560", (120, 36), (*MOVE, "4", "z")),
    ("views-3d-orbited-fit-120x36", "puma560", (120, 36), (*MOVE, "4", "z", "d", "w")),
    ("views-frames-ends-120x36", "puma560", (120, 36), (*MOVE, "x")),
    ("views-zoomed-120x36", "puma560", (120, 36), (*MOVE, "plus", "plus")),
    ("control-200x60", "puma560", (200, 60), MOVE),
    ("views-workspace-120x36", "puma560", (120, 36), (*MOVE, "W")),
    (
        "control-80x24",
        "puma560",
        (80, 24),
        MOVE,
    ),
    ("palette-80x24", "puma560", (80, 24), ("ctrl+p", "g", "o", " ", "t", "o")),
    (
        "control-160x48",
        "puma560",
        (160, 48),
        MOVE,
    ),
    (
        "control-stanford-160x48",
        "stanford",
        (160, 48),
        (
            "right_square_bracket",
            "right_square_bracket",
            "right",
            "right",
            "down",
            "down",
            "right_square_bracket",
            "right",
            "right",
            "right",
        ),
    ),
    (
        "control-scara-pedestal-80x24",
        "scara_pedestal",
        (80, 24),
        (
            "right_square_bracket",
            "right_square_bracket",
            "right",
            "right",
            "down",
            "left",
            "left",
            "left",
        ),
    ),
    ("help-80x24", "puma560", (80, 24), ("question_mark",)),
    # the demo program: its panel, its path in every view, at the start of step 3
    ("program-120x36", "puma560", (120, 36), ("g", "full_stop", "full_stop")),
    ("program-plot-100x30", "puma560", (100, 30), ("g", "full_stop", "full_stop", "t")),
    (
        "cartesian-160x48",
        "puma560",
        (160, 48),
        (
            "p",
            "p",
            "p",
            "p",
            "c",
            "right_square_bracket",
            "right",
            "right",
            "right",
            "right",
            "right",
            "down",
            "down",
            "left",
            "left",
            "left",
        ),
    ),
    (
        "editor-80x24",
        "scara_pedestal",
        (80, 24),
        ("e", "down", "right", "right", "right", "right", "right"),
    ),
    (
        "editor-160x48",
        "scara_pedestal",
        (160, 48),
        ("e", "down", "right", "right", "right", "right", "right"),
    ),
]


async def shoot(name: str, robot_name: str, size: tuple[int, int], keys: tuple[str, ...]) -> None:
    robot, path = load_robot(robot_name)
    mode = dict(VIEW_MODES.get(name, {}))
    # what a truecolor terminal shows, unless the shot is of another depth
    color_system = mode.pop("color_system", "truecolor")
    if mode.pop("no_color", False):
        os.environ["NO_COLOR"] = "1"  # Textual reads it when the app is made
    app = DhsimApp(robot, path, animate=False, **mode)  # moves land at once: the same shot
    os.environ.pop("NO_COLOR", None)
    # as TERM=xterm (16 colours), xterm-256color or COLORTERM=truecolor gets
    app.console._color_system = {
        "standard": ColorSystem.STANDARD,
        "256": ColorSystem.EIGHT_BIT,
        "truecolor": ColorSystem.TRUECOLOR,
    }[color_system]
    async with app.run_test(size=size) as pilot:
        await pilot.press(*keys)
        screen = app.screen
        if isinstance(screen, ControlScreen):  # the footer as dhsim starts: "m Motion on"
            screen.animate = True
            screen.refresh_bindings()
        await pilot.pause()
        await app.workers.wait_for_complete()  # the workspace cloud is sampled in a worker
        await pilot.pause()
        (HERE / f"{name}.svg").write_text(export_svg(app), encoding="utf-8")


#: ``dhsim draw`` pictures: (file name, its arguments)
DRAWINGS = [
    ("draw-puma560.svg", ["puma560", "--q", "0,45,-45,0,30,0"]),
    ("draw-puma560-fit.svg", ["puma560", "--q", "0,45,-45,0,30,0", "--fit"]),
    ("draw-stanford-front.svg", ["stanford", "--view", "front", "--q", "20,-30,600,0,40,0"]),
]


def main() -> None:
    from dhsim_tui.cli.main import main as dhsim

    prefixes = tuple(sys.argv[1:])
    for shot in SHOTS:
        if prefixes and not shot[0].startswith(prefixes):
            continue
        asyncio.run(shoot(*shot))
        print(f"screenshots/{shot[0]}.svg")
    for name, args in DRAWINGS:
        if prefixes and not name.startswith(prefixes):
            continue
        dhsim(["draw", *args, "-o", str(HERE / name), "--force"])


if __name__ == "__main__":
    main()
