"""End to end, the real ``dhsim`` in a terminal (issue 27 §1): ``dhsim new``
run from a folder that has a ``robots/`` folder (a source checkout's, say)
saves into the user library, and ``dhsim list`` then shows the robot as
yours, not as bundled."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest
from pty_screen import PtyScreen, dhsim_command
from waiting import HANG, wait_until

from dhsim_tui.core import load


@pytest.fixture
def short_data():
    """A user library's data folder with a path short enough for the save
    dialog to show it on one line (48 columns)."""
    folder = Path(tempfile.mkdtemp(prefix="d", dir="/tmp"))
    yield folder
    shutil.rmtree(folder, ignore_errors=True)


def test_dhsim_new_saves_in_the_user_library_and_list_shows_it_as_yours(tmp_path, short_data):
    work = tmp_path / "work"
    (work / "robots").mkdir(parents=True)
    data = short_data
    target = data / "dhsim" / "robots" / "irb120.toml"
    env = {"XDG_DATA_HOME": str(data)}
    with PtyScreen(["new", "irb120"], size=(100, 30), env=env, cwd=work) as shell:
        shell.wait_for("number of joints")
        shell.send("enter")  # three revolute rows
        shell.wait_for("irb120")
        shell.send("ctrl+s")
        shell.wait_for(str(target))  # the full path, before anything is written
        assert not target.exists()
        shell.send("enter")
        wait_until(target.exists, "the robot saved in the user library")
        shell.wait_for("saved")
        shell.send("escape")  # the editor, then the simulator on the saved robot
        shell.wait_for("q Quit")
        shell.send("q")
        assert shell.wait_exit() == 0
    assert load(target).name == "irb120" and load(target).dof == 3
    assert list((work / "robots").iterdir()) == []

    listing = subprocess.run(
        [dhsim_command(), "list", "--json"],
        cwd=work,
        env={**os.environ, **env},
        capture_output=True,
        timeout=HANG,
        check=False,
    )
    assert (listing.returncode, listing.stderr) == (0, b"")
    listed = json.loads(listing.stdout)
    assert [(e["name"], e["path"]) for e in listed["yours"]] == [("irb120", str(target))]
    assert "irb120" not in [e["name"] for e in listed["bundled"]]
    text = subprocess.run(
        [dhsim_command(), "list"],
        cwd=work,
        env={**os.environ, **env},
        capture_output=True,
        timeout=HANG,
        check=False,
    ).stdout.decode()
    yours, bundled = text.split("\nbundled:\n")
    assert "irb120" in yours and str(target) in yours and "irb120" not in bundled
