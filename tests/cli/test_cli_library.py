"""`dhsim list`, `dhsim new` and a robot's name on the command line, with a
user library (issue 27 §1: your robots are yours)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from dhsim_tui.cli import main as cli
from dhsim_tui.cli.library import new_target, opened_notice
from dhsim_tui.cli.main import main
from dhsim_tui.core.files.library import bundled_names, bundled_path, load_robot
from dhsim_tui.core.model.errors import RobotFileError


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


@pytest.fixture
def mine(tmp_path, monkeypatch) -> Path:
    """This test's user library (not made yet: dhsim makes it when saving)."""
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    return tmp_path / "data" / "dhsim" / "robots"


def _copy(name: str, to: Path, robot_name: str) -> Path:
    to.parent.mkdir(parents=True, exist_ok=True)
    original = load_robot(name)[0].name
    text = bundled_path(name).read_text(encoding="utf-8")
    to.write_text(text.replace(f'"{original}"', f'"{robot_name}"'), encoding="utf-8")
    return to


def _groups(out: str) -> tuple[str, list[str], list[str]]:
    """The "yours" header line, your robots' lines and the bundled ones'."""
    lines = out.splitlines()
    assert lines[0].startswith("yours")
    split = lines.index("bundled:")
    return lines[0], lines[1:split], lines[split + 1 :]


# -- dhsim list ----------------------------------------------------------------------


def test_list_with_no_robots_of_yours_says_where_they_would_go(capsys, mine):
    code, out, err = run(capsys, "list")
    assert (code, err) == (0, "")
    header, yours, bundled = _groups(out)
    assert header == f"yours ({mine}): none yet ('dhsim new NAME' saves one there)"
    assert yours == []
    assert [line.split()[0] for line in bundled] == bundled_names()


def test_list_shows_yours_with_their_paths_then_the_bundled_ones(capsys, mine):
    _copy("irb140", mine / "irb120.toml", "ABB IRB 120")
    _copy("puma560", mine / "puma560.toml", "My Puma")
    code, out, err = run(capsys, "list")
    assert (code, err) == (0, "")
    header, yours, bundled = _groups(out)
    assert header == f"yours ({mine}):"
    assert [line.split()[0] for line in yours] == ["irb120", "puma560"]
    assert "ABB IRB 120: 6 joints" in yours[0] and yours[0].endswith(f"({mine / 'irb120.toml'})")
    assert "My Puma" in yours[1]
    assert [line.split()[0] for line in bundled] == bundled_names()  # irb120 not among them
    puma = next(line for line in bundled if line.split()[0] == "puma560")
    assert "Puma 560: 6 joints" in puma and "My Puma" not in puma


def test_list_json_has_yours_and_bundled(capsys, mine):
    _copy("irb140", mine / "irb120.toml", "ABB IRB 120")
    code, out, err = run(capsys, "list", "--json")
    assert (code, err) == (0, "")
    listed = json.loads(out)
    assert listed["library"] == str(mine)
    assert listed["yours"] == [
        {
            "name": "irb120",
            "path": str(mine / "irb120.toml"),
            "robot": "ABB IRB 120",
            "dof": 6,
            "types": "RRRRRR",
            "convention": "standard",
            "units": "mm",
            "reach": 1138.7,
        }
    ]
    assert [entry["name"] for entry in listed["bundled"]] == bundled_names()
    puma = next(entry for entry in listed["bundled"] if entry["name"] == "puma560")
    assert puma["path"] == str(bundled_path("puma560"))
    assert (puma["robot"], puma["dof"], puma["reach"]) == ("Puma 560", 6, 877.01)


def test_a_broken_file_of_yours_is_listed_with_the_reason(capsys, mine):
    mine.mkdir(parents=True)
    (mine / "broken.toml").write_text("name = \n", encoding="utf-8")
    code, out, err = run(capsys, "list")
    assert (code, err) == (0, "")
    _, yours, _ = _groups(out)
    assert len(yours) == 1 and yours[0].split()[0] == "broken"
    assert "(cannot be opened: " in yours[0] and str(mine / "broken.toml") in yours[0]
    code, out, _ = run(capsys, "list", "--json")
    (entry,) = json.loads(out)["yours"]
    assert entry["name"] == "broken" and entry["error"] and "robot" not in entry


def test_list_escapes_a_hostile_file_name(capsys, mine):
    _copy("planar2", mine / "arm\x1b]0;owned\x07.toml", "arm")
    code, out, err = run(capsys, "list")
    assert (code, err) == (0, "")
    assert "\x1b" not in out and "\x07" not in out and "\\x1b]0;owned\\x07" in out


def test_list_refuses_an_extra_argument(capsys, mine):
    code, out, err = run(capsys, "list", "extra")
    assert code == 2 and out == "" and "extra" in err


# -- a name on the command line: yours first, and said on stderr -------------------


def test_a_name_of_yours_hiding_a_bundled_one_is_said_on_stderr_not_stdout(capsys, mine):
    _copy("puma560", mine / "puma560.toml", "My Puma")
    code, out, err = run(capsys, "fk", "puma560", "--json")
    assert code == 0
    assert json.loads(out)  # stdout is the data alone
    assert err == f"dhsim: opened your puma560 (not the bundled one): {mine / 'puma560.toml'}\n"
    code, out, err = run(capsys, "check", "puma560")
    assert code == 0 and "My Puma" in out and str(mine / "puma560.toml") in out


def test_a_name_only_you_have_opens_quietly(capsys, mine):
    _copy("irb140", mine / "irb120.toml", "ABB IRB 120")
    code, out, err = run(capsys, "check", "irb120")
    assert (code, err) == (0, "")
    assert "ABB IRB 120" in out and str(mine / "irb120.toml") in out
    code, out, err = run(capsys, "check", "puma560")
    assert (code, err) == (0, "") and "Puma 560" in out


def test_the_simulator_is_told_which_robot_a_name_opened(capsys, mine, monkeypatch):
    _copy("puma560", mine / "puma560.toml", "My Puma")
    calls = []
    monkeypatch.setattr(cli, "has_terminal", lambda: True)
    monkeypatch.setattr("dhsim_tui.tui.app.run_app", lambda *a, **k: calls.append((a, k)) or 0)
    assert run(capsys, "puma560") == (0, "", "")
    (args, kwargs), *_ = calls
    assert args[1] == mine / "puma560.toml" and args[0].name == "My Puma"
    assert kwargs["notice"] == (
        f"opened your puma560 (not the bundled one): {mine / 'puma560.toml'}"
    )
    assert opened_notice("stanford") == "opened the bundled stanford"
    assert opened_notice(str(mine / "puma560.toml")) is None  # a path says itself
    assert opened_notice(None) is None and opened_notice("nosuch") is None


# -- dhsim new -------------------------------------------------------------------------


def test_new_passes_the_path_given_and_none_by_default(capsys, tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(cli, "has_terminal", lambda: True)
    monkeypatch.setattr("dhsim_tui.tui.app.run_app", lambda *a, **k: calls.append(k) or 0)
    assert run(capsys, "new", "irb120") == (0, "", "")
    assert calls[-1]["new_target"] is None  # the save dialog offers the user library
    assert run(capsys, "new", "irb120", "-o", str(tmp_path / "arms" / "irb120")) == (0, "", "")
    assert calls[-1]["new_target"] == tmp_path / "arms" / "irb120.toml"


def test_new_refuses_a_folder_as_its_file(capsys, tmp_path, monkeypatch):
    monkeypatch.setattr(cli, "has_terminal", lambda: True)
    monkeypatch.setattr("dhsim_tui.tui.app.run_app", lambda *a, **k: 0)
    (tmp_path / "arms.toml").mkdir()
    code, out, err = run(capsys, "new", "irb120", "-o", str(tmp_path / "arms.toml"))
    assert (code, out) == (2, "") and "is a folder; give a file name" in err


def test_new_target_is_a_full_toml_path(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert new_target(None) is None
    assert new_target("arm") == tmp_path / "arm.toml"
    assert new_target("sub/arm.toml") == tmp_path / "sub" / "arm.toml"
    with pytest.raises(RobotFileError, match="empty"):
        new_target("  ")
