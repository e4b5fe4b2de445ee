"""Shared fixtures: the bundled robots and an independent FK written straight
from the reference's formulas (plain 4×4 products), to check the core against."""

from __future__ import annotations

import atexit
import math
import os
import shutil
import tempfile
from pathlib import Path

import numpy as np
import pytest

from dhsim_tui.core import bundled_names, load_robot

BUNDLED = bundled_names()


def _rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _ry(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1.0]])


def _trans(x, y, z):
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


_AXIS = {
    "+x": (1, 0, 0),
    "-x": (-1, 0, 0),
    "+y": (0, 1, 0),
    "-y": (0, -1, 0),
    "+z": (0, 0, 1),
    "-z": (0, 0, -1),
}


def reference_frames(robot, q):
    """Frames 0..n and the tool, by the reference's formulas (§1, §3)."""
    x = np.array(_AXIS[robot.base_x], float)
    z = np.array(_AXIS[robot.base_z], float)
    m = np.eye(4)
    m[:3, :3] = np.column_stack([x, np.cross(z, x), z])
    roll, pitch, yaw = (math.radians(v) for v in robot.base_rpy)
    m = _trans(*robot.base_xyz) @ m @ _rz(yaw) @ _ry(pitch) @ _rx(roll)
    frames = [m]
    for joint, value in zip(robot.joints, q, strict=True):
        variable = value + joint.offset  # the D-H variable is q + offset
        theta = math.radians(variable if joint.is_revolute else joint.theta)
        d = joint.d if joint.is_revolute else variable
        alpha = math.radians(joint.alpha)
        if robot.convention == "standard":
            t = _rz(theta) @ _trans(0, 0, d) @ _trans(joint.a, 0, 0) @ _rx(alpha)
        else:
            t = _rx(alpha) @ _trans(joint.a, 0, 0) @ _rz(theta) @ _trans(0, 0, d)
        m = m @ t
        frames.append(m)
    roll, pitch, yaw = (math.radians(v) for v in robot.tool.rpy)
    tool = _trans(*robot.tool.xyz) @ _rz(yaw) @ _ry(pitch) @ _rx(roll)
    frames.append(m @ tool)
    return np.array(frames)


def random_q(robot, rng, count=None):
    low = np.array(robot.lower)
    high = np.array(robot.upper)
    shape = (robot.dof,) if count is None else (count, robot.dof)
    return rng.uniform(low, high, size=shape)


@pytest.fixture(params=BUNDLED)
def bundled(request):
    robot, _ = load_robot(request.param)
    return robot


@pytest.fixture
def puma():
    return load_robot("puma560")[0]


@pytest.fixture
def rng():
    return np.random.default_rng(20101217)


@pytest.fixture
def in_tmp(tmp_path, monkeypatch):
    """A fresh working folder (so robots/ is a new one) and recovery folder.
    Modules that want it for every test say ``pytestmark =
    pytest.mark.usefixtures("in_tmp")``; some define their own."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("DHSIM_RECOVERY_DIR", str(tmp_path / "recovery"))
    return tmp_path


#: the folders of the terminal UI's tests (Textual's Pilot, a pseudo-terminal);
#: the rest are the core's, the scene's and the command line's, which .ci/run
#: also runs under every Python it finds
UI_FOLDERS = ("tui", "pty")
#: folders whose every test is ``slow``: the whole app driven by Pilot, and the
#: real dhsim in a pseudo-terminal (together four fifths of the suite's time:
#: each starts the app and waits on it); ``-m "not slow"`` is the quick loop
SLOW_FOLDERS = ("tui", "pty")

#: variables of the user's session that change what dhsim does; the tests
#: run without them, whatever shell started pytest (a test that wants one
#: sets it itself)
SESSION_VARIABLES = (
    "NO_COLOR",
    "FORCE_COLOR",
    "COLORTERM",
    "TEXTUAL",
    "TEXTUAL_FPS",
    "COLUMNS",
    "LINES",
    "LC_ALL",
    "LC_CTYPE",
    "LC_MESSAGES",
    "LANGUAGE",
)


def _isolate_environment() -> None:
    """The suite runs the same wherever it runs: its own HOME and XDG
    folders (no user library, config or recovery files of the person running
    it), a UTF-8 locale, no colour or size overrides, no DHSIM_* setting.
    Set before any test runs, so every subprocess and pseudo-terminal the
    tests start inherits it."""
    home = Path(tempfile.mkdtemp(prefix="dhsim-tests-home-"))
    atexit.register(shutil.rmtree, home, ignore_errors=True)
    for name in list(os.environ):
        if name.startswith("DHSIM_") and name != "DHSIM_TEST_HANG":
            del os.environ[name]
    for name in SESSION_VARIABLES:
        os.environ.pop(name, None)
    os.environ["HOME"] = str(home)
    for name, folder in (
        ("XDG_DATA_HOME", ".local/share"),
        ("XDG_CONFIG_HOME", ".config"),
        ("XDG_STATE_HOME", ".local/state"),
        ("XDG_CACHE_HOME", ".cache"),
    ):
        os.environ[name] = str(home / folder)
    os.environ["XDG_RUNTIME_DIR"] = str(home / "run")
    (home / "run").mkdir(mode=0o700)
    os.environ["DHSIM_RECOVERY_DIR"] = str(home / "recovery")
    os.environ["LANG"] = "C.UTF-8"
    os.environ.setdefault("TERM", "xterm-256color")


def pytest_configure(config):
    config.addinivalue_line("markers", "ui: drives the terminal UI (Textual, a pseudo-terminal)")
    config.addinivalue_line(
        "markers",
        "slow: a pseudo-terminal, a monkey or a long hypothesis run; "
        '-m "not slow" is the quick loop',
    )
    _isolate_environment()


def pytest_collection_modifyitems(config, items):
    """Mark every test in a UI folder ``ui`` (``-m "not ui"`` runs the core's,
    the scene's and the command line's alone) and every test of the whole
    app (Pilot, a pseudo-terminal) ``slow``."""
    for item in items:
        if item.path.parent.name in UI_FOLDERS:
            item.add_marker(pytest.mark.ui)
        if item.path.parent.name in SLOW_FOLDERS:
            item.add_marker(pytest.mark.slow)


@pytest.fixture(autouse=True)
def _own_working_folder(tmp_path_factory, monkeypatch):
    """Every test starts in a fresh, empty working folder: none reads or
    writes the repository's ``robots/`` or litters the checkout (a test that
    wants ``tmp_path`` there too uses ``in_tmp``)."""
    monkeypatch.chdir(tmp_path_factory.mktemp("cwd"))


@pytest.fixture(autouse=True)
def _own_robot_library(tmp_path_factory, monkeypatch):
    """Every test has its own, empty user robot library
    (``$XDG_DATA_HOME/dhsim/robots``): a robot one test saves there is not
    listed, opened or replaced by another."""
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path_factory.mktemp("data")))
