"""Your robots are yours (issue 27 §1): the user library, and how a robot's
name is looked up in it before the bundled robots."""

from __future__ import annotations

from pathlib import Path

import pytest

from dhsim_tui.core import load_robot, resolve
from dhsim_tui.core.files import library
from dhsim_tui.core.files.library import (
    bundled_path,
    find,
    in_user_library,
    is_bundled_file,
    user_library_dir,
    user_path,
    user_robots,
)
from dhsim_tui.core.model.errors import RobotFileError


@pytest.fixture
def mine(tmp_path, monkeypatch) -> Path:
    """A user library of its own, holding nothing yet."""
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    folder = tmp_path / "data" / "dhsim" / "robots"
    folder.mkdir(parents=True)
    return folder


def _copy(name: str, to: Path, robot_name: str) -> Path:
    text = bundled_path(name).read_text(encoding="utf-8")
    original = load_robot(name)[0].name
    to.write_text(text.replace(f'"{original}"', f'"{robot_name}"'), encoding="utf-8")
    return to


# -- where the library is ----------------------------------------------------------


def test_the_library_is_under_xdg_data_home(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "share"))
    assert user_library_dir() == tmp_path / "share" / "dhsim" / "robots"


@pytest.mark.parametrize("value", [None, "", "relative/share"])
def test_without_an_absolute_xdg_data_home_it_is_under_the_home_folder(
    tmp_path, monkeypatch, value
):
    """The XDG rule: unset, empty or relative means the default."""
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    if value is None:
        monkeypatch.delenv("XDG_DATA_HOME", raising=False)
    else:
        monkeypatch.setenv("XDG_DATA_HOME", value)
    assert user_library_dir() == tmp_path / "home" / ".local" / "share" / "dhsim" / "robots"


def test_without_a_home_folder_the_library_is_an_error_and_names_still_work(monkeypatch):
    monkeypatch.delenv("XDG_DATA_HOME", raising=False)

    def no_home():
        raise RuntimeError("Could not determine home directory.")

    monkeypatch.setattr(Path, "home", staticmethod(no_home))
    with pytest.raises(RobotFileError, match="set HOME or XDG_DATA_HOME"):
        user_library_dir()
    assert user_robots() == [] and user_path("puma560") is None
    assert find("puma560").origin == "bundled"


# -- what is in it ----------------------------------------------------------------


def test_the_library_lists_its_robot_files_by_name(mine):
    for name in ("zeta.toml", "Alpha.toml", "notes.txt", ".hidden.toml"):
        (mine / name).write_text("")
    (mine / "folder").mkdir()
    assert [p.name for p in user_robots()] == ["Alpha.toml", "zeta.toml"]


def test_no_library_yet_lists_nothing(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "nothing-here"))
    assert user_robots() == []
    assert find("puma560").origin == "bundled"


def test_a_library_that_cannot_be_read_says_so(mine, monkeypatch):
    def refused(path):
        raise PermissionError(13, "Permission denied", str(path))

    monkeypatch.setattr(library.os, "scandir", refused)
    notes: list[str] = []
    assert user_robots(notes) == []
    assert len(notes) == 1 and str(mine) in notes[0] and "permission denied" in notes[0]


# -- a name: yours first, then bundled; a path is a path --------------------------


def test_a_name_finds_your_robot_before_the_bundled_one(mine):
    _copy("puma560", mine / "puma560.toml", "My Puma")
    found = find("puma560")
    assert (found.path, found.origin) == (mine / "puma560.toml", "yours")
    assert found.shadows == bundled_path("puma560")
    assert load_robot("puma560")[0].name == "My Puma"
    assert resolve("puma560") == mine / "puma560.toml"
    assert "not the bundled one" in found.opened() and str(mine) in found.opened()


def test_a_name_only_you_have_is_found_and_said_to_be_yours(mine):
    _copy("irb140", mine / "irb120.toml", "ABB IRB 120")
    for argument in ("irb120", "irb120.toml", "IRB120"):
        found = find(argument)
        assert (found.path, found.origin, found.shadows) == (mine / "irb120.toml", "yours", None)
    assert load_robot("irb120")[0].name == "ABB IRB 120"
    assert found.opened() == f"opened your irb120: {mine / 'irb120.toml'}"


def test_a_bundled_name_you_do_not_have_is_the_bundled_robot(mine):
    found = find("stanford")
    assert (found.path, found.origin) == (bundled_path("stanford"), "bundled")
    assert found.opened() == "opened the bundled stanford"


def test_a_path_is_a_path_never_a_name(mine, tmp_path, monkeypatch):
    _copy("puma560", mine / "puma560.toml", "My Puma")
    here = tmp_path / "here"
    (here / "robots").mkdir(parents=True)
    monkeypatch.chdir(here)
    _copy("puma560", here / "robots" / "puma560.toml", "Puma in robots/")
    found = find("robots/puma560.toml")
    assert (found.path, found.origin) == (Path("robots/puma560.toml"), "path")
    assert found.opened() == "opened robots/puma560.toml"
    with pytest.raises(RobotFileError) as caught:
        find("robots/irb120")  # a slash: not looked up in the library, nor as bundled
    assert str(caught.value) == "robots/irb120: no such file"


def test_an_unknown_name_says_where_it_looked(mine):
    with pytest.raises(RobotFileError) as caught:
        find("irb120")
    message = str(caught.value)
    assert "irb120: no such file" in message and str(mine) in message
    assert "puma560" in message and "dhsim list" in message


def test_a_name_with_control_characters_is_shown_escaped(mine):
    hostile = "arm\x1b[2J"
    _copy("planar2", mine / f"{hostile}.toml", "hostile")
    found = find(hostile)
    assert found.origin == "yours" and "\x1b" not in found.opened()
    assert "\\x1b" in found.opened()


# -- your files are never bundled --------------------------------------------------


def test_your_file_is_never_bundled_even_with_a_bundled_name(mine):
    _copy("puma560", mine / "puma560.toml", "My Puma")
    assert not is_bundled_file(mine / "puma560.toml")
    assert is_bundled_file(bundled_path("puma560"))
    assert in_user_library(mine / "puma560.toml")
    assert not in_user_library(bundled_path("puma560"))
