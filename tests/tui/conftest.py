"""What the terminal UI's tests share: the app made for the simulator or the
editor, the status line's message and the composed screen as text. Waiting
and pressing keys are in tests/pilot_helpers.py; robot files the tests load
are in tests/data/robots/ (:func:`robot_text`).

The helpers are plain functions. A test takes them as the fixtures
``control_app``, ``editor_app``, ``status`` and ``screen_text``; a test
module imports them (``from tui.conftest import control, editor``:
tests/tui is a package, so this conftest is ``tui.conftest``, the module
pytest loaded)."""

from __future__ import annotations

from pathlib import Path

import pytest

from dhsim_tui.core import load_robot
from dhsim_tui.core.model.editing import set_pose
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.editor import EditorScreen

ROBOTS = Path(__file__).parent.parent / "data" / "robots"


def make_control_app(name: str = "puma560", *, q=None, animate: bool = False, **kwargs) -> DhsimApp:
    """The simulator on the robot ``name`` (bundled or a file), its start
    pose ``q`` if given. Motion is off unless a test asks for it (moves land
    at once); ``kwargs`` go to :class:`DhsimApp` (``renderer``, ...)."""
    robot, path = load_robot(name)
    if q is not None:
        robot = set_pose(robot, "start", q)
    return DhsimApp(robot, path, animate=animate, **kwargs)


def make_editor_app(robot=None, path=None, *, animate: bool = False, **kwargs) -> DhsimApp:
    """The app opening in the table editor: on ``robot`` (from ``path``), the
    bundled Puma 560 if none. Motion is off unless a test asks for it."""
    if robot is None:
        robot, path = load_robot("puma560")
    kwargs.setdefault("start", "edit")
    return DhsimApp(robot, path, animate=animate, **kwargs)


def control(app: DhsimApp) -> ControlScreen:
    """The simulator's screen, checked to be the one in front."""
    assert isinstance(app.screen, ControlScreen)
    return app.screen


def editor(app: DhsimApp) -> EditorScreen:
    """The topmost table editor, even under a dialog."""
    for screen in reversed(app.screen_stack):
        if isinstance(screen, EditorScreen):
            return screen
    raise AssertionError("no editor")


def status_of(app: DhsimApp) -> str:
    """The status line's message: the editor's (the topmost editor, even
    under a dialog) or else the simulator's in front."""
    for screen in reversed(app.screen_stack):
        if isinstance(screen, EditorScreen):
            return str(screen.query_one("#editor-status").render())
        if isinstance(screen, ControlScreen):
            break
    return str(app.screen.query_one("#status").render())


def screen_strips(app: DhsimApp) -> list:
    """The composed screen in front, a :class:`textual.strip.Strip` per row
    (``strip.text``, ``strip.crop(x1, x2)``).

    Textual has no public way to read the composed screen (a widget's
    ``render()`` gives that widget alone, ``export_screenshot()`` an SVG), so
    this is the one place the tests read its private ``_compositor``."""
    return app.screen._compositor.render_strips()


def text_of(app: DhsimApp) -> str:
    """What a person sees: the composed screen as plain text, a line per row."""
    return "\n".join(strip.text for strip in screen_strips(app))


def robot_text(name: str) -> str:
    """The text of ``tests/data/robots/<name>.toml``."""
    return (ROBOTS / f"{name}.toml").read_text(encoding="utf-8")


@pytest.fixture
def control_app():
    """:func:`make_control_app`: ``app = control_app()``, ``control_app("scara", q=...)``."""
    return make_control_app


@pytest.fixture
def editor_app():
    """:func:`make_editor_app`: ``app = editor_app()``, ``editor_app(robot, path)``."""
    return make_editor_app


@pytest.fixture
def status():
    """:func:`status_of`: ``status(app)``."""
    return status_of


@pytest.fixture
def screen_text():
    """:func:`text_of`: ``screen_text(app)``."""
    return text_of
