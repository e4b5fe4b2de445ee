"""Where the command line's output goes, and the small promises of its input.

Output that cannot be written (a full disk, standard output closed) is one
plain line on stderr and status 2, never "internal error"; a reader that
stops early stays a quiet status 0. ``-o ''`` says the name is empty. Numbers
are ASCII digits. An option given twice is refused. Counts agree with their
nouns, and a long name is shortened in the middle.
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest
from pty_screen import dhsim_command
from waiting import HANG

from dhsim_tui.cli.main import main
from dhsim_tui.core.model.text import SHOWN_CHARS, counted, shortened

URDFS = Path(__file__).resolve().parents[1] / "urdfs"
ONE_JOINT = 'name = "{name}"\n[[joints]]\ntheta = 0.0\nd = 0.0\na = 100.0\nalpha = 0.0\n'


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def one_line_error(capsys, *argv: str) -> str:
    code, out, err = run(capsys, *argv)
    assert (code, out) == (2, ""), (code, out, err)
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err, err
    return err.strip()


def dhsim(*argv: str, **kwargs) -> subprocess.CompletedProcess[bytes]:
    kwargs.setdefault("stderr", subprocess.PIPE)
    return subprocess.run(
        [dhsim_command(), *argv], stdin=subprocess.DEVNULL, timeout=HANG, check=False, **kwargs
    )


# -- output that cannot be written ------------------------------------------------------

FULL_COMMANDS = [
    ["fk", "puma560"],
    ["check", "puma560"],
    ["list"],
    ["export", "puma560", "--format", "urdf"],  # larger than a buffer: fails mid-command
    ["--version"],
    ["fk", "--help"],  # argparse's own help, then its exit
]


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
@pytest.mark.parametrize("argv", FULL_COMMANDS, ids=" ".join)
def test_a_full_disk_is_one_plain_line_and_status_2(argv):
    with open("/dev/full", "wb") as full:
        result = dhsim(*argv, stdout=full)
    assert result.returncode == 2
    assert result.stderr == b"dhsim: cannot write the output: no space left on device\n"


def _close_stdout() -> None:
    os.close(1)


@pytest.mark.parametrize("argv", [["fk", "puma560"], ["list"], ["draw", "planar2"]], ids=" ".join)
def test_standard_output_closed_is_one_plain_line_and_status_2(argv):
    result = dhsim(*argv, preexec_fn=_close_stdout)  # as `dhsim fk puma560 >&-`
    assert result.returncode == 2
    assert result.stderr == b"dhsim: cannot write the output: standard output is closed\n"


def test_with_standard_output_closed_nothing_is_written_to_a_file_either(tmp_path):
    target = tmp_path / "puma.urdf"
    result = dhsim(
        "export", "puma560", "--format", "urdf", "-o", str(target), preexec_fn=_close_stdout
    )
    assert result.returncode == 2 and b"standard output is closed" in result.stderr
    assert not target.exists()


@pytest.mark.parametrize(
    "argv", [["fk", "puma560"], ["export", "puma560", "--format", "urdf"]], ids=" ".join
)
def test_a_reader_that_stops_early_is_still_a_quiet_status_0(argv):
    reader, writer = os.pipe()
    os.close(reader)  # `| head -0`: the reader is gone before a byte is written
    try:
        result = dhsim(*argv, stdout=writer)
    finally:
        os.close(writer)
    assert (result.returncode, result.stderr) == (0, b"")


# -- -o '' ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "argv",
    [
        ["export", "puma560", "--format", "urdf", "-o", ""],
        ["export", "puma560", "--format", "json", "--output="],
        ["convert", "puma560", "--convention", "modified", "-o", ""],
        ["import", str(URDFS / "planar_elbow.urdf"), "-o", ""],
        ["draw", "planar2", "-o", ""],
    ],
    ids=lambda argv: argv[0],
)
def test_an_empty_output_name_is_called_empty(capsys, argv, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    message = one_line_error(capsys, *argv)
    assert "-o: the file name is empty" in message
    assert "folder" not in message
    assert list(tmp_path.iterdir()) == []


# -- numbers are ASCII -----------------------------------------------------------------

ARABIC_ONE = "\u0661"  # ١, which float() and int() read as 1


@pytest.mark.parametrize(
    ("argv", "fragments"),
    [
        (["fk", "puma560", "--q", f"{ARABIC_ONE},0,0,0,0,0"], ["--q: item 1", "ASCII"]),
        (["fk", "planar2", "--q", f"0,{ARABIC_ONE}0"], ["--q: item 2", "ASCII"]),
        (["fk", "planar2", "--q", "0,\uff11"], ["--q: item 2"]),  # a fullwidth 1
        (["ik", "planar2", "--xyz", f"1,{ARABIC_ONE},0"], ["--xyz: item 2"]),
        (["ik", "puma560", "--xyz", "400,0,400", "--oat", f"0,0,{ARABIC_ONE}"], ["--oat: item 3"]),
        (["ik", "planar2", "--xyz", "1,1,0", "--from", f"{ARABIC_ONE},0"], ["--from: item 1"]),
        (["draw", "planar2", "--orbit", f"{ARABIC_ONE}0,30"], ["--orbit: item 1"]),
        (["draw", "planar2", "--size", f"{ARABIC_ONE}00x600"], ["--size"]),
        (["workspace", "planar2", "--n", f"{ARABIC_ONE}0"], ["--n", "ASCII digits"]),
        (["workspace", "planar2", "--seed", ARABIC_ONE], ["--seed", "ASCII digits"]),
    ],
    ids=lambda value: value[1] if isinstance(value, list) and len(value) > 1 else None,
)
def test_numbers_on_the_command_line_are_ascii_digits(capsys, argv, fragments):
    message = one_line_error(capsys, *argv)
    for fragment in fragments:
        assert fragment in message, message


def test_ascii_numbers_of_every_form_still_work(capsys):
    code, out, err = run(capsys, "fk", "planar2", "--q", " +1.5e1 , -2.5 ")
    assert code == 0, err
    assert "Th1 15  Th2 -2.5" in out


# -- an option given twice -----------------------------------------------------------


@pytest.mark.parametrize(
    ("argv", "option"),
    [
        (["fk", "puma560", "--q", "1,2,3,4,5,6", "--q", "0,0,0,0,0,0"], "--q"),
        (["fk", "puma560", "--q=0,0,0,0,0,0", "--q", "-1,0,0,0,0,0"], "--q"),
        (["fk", "puma560", "--pose", "qz", "--pose", "qr"], "--pose"),
        (["ik", "planar2", "--xyz", "1,1,0", "--xyz", "1,0,0"], "--xyz"),
        (["ik", "planar2", "--xyz", "1,1,0", "--from", "0,0", "--from", "1,1"], "--from"),
        (["export", "puma560", "--format", "csv", "--format", "json"], "--format"),
        (["export", "puma560", "--format", "csv", "-o", "a.csv", "--output", "b.csv"], "-o"),
        (["workspace", "planar2", "--n", "10", "--n", "20"], "--n"),
        (["draw", "planar2", "--view", "top", "--view", "side"], "--view"),
        (["--renderer", "braille", "--renderer", "plotext"], "--renderer"),
    ],
    ids=lambda value: value if isinstance(value, str) else None,
)
def test_an_option_given_twice_is_refused_naming_it(capsys, argv, option, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    message = one_line_error(capsys, *argv)
    assert f"argument {option}" in message and "more than once" in message
    assert list(tmp_path.iterdir()) == []  # refused before anything was written


def test_a_flag_or_an_option_given_once_is_fine(capsys):
    code, out, err = run(capsys, "fk", "puma560", "--json", "--q", "0,0,0,0,0,0")
    assert code == 0 and out.startswith("{"), err


# -- counts and their nouns --------------------------------------------------------


def test_counted_agrees():
    assert [counted(n, "joint") for n in (0, 1, 2)] == ["0 joints", "1 joint", "2 joints"]
    assert counted(1, "family", "families") == "1 family"
    assert counted(3, "family", "families") == "3 families"


def test_one_joint_is_a_joint(capsys, tmp_path):
    path = tmp_path / "one.toml"
    path.write_text(ONE_JOINT.format(name="one"), encoding="utf-8")
    code, out, _ = run(capsys, "check", str(path))
    assert code == 0 and "one: 1 joint, R," in out
    message = one_line_error(capsys, "fk", str(path), "--q", "1,2")
    assert "expected 1 joint value (Th1), got 2" in message
    code, out, _ = run(capsys, "workspace", str(path), "--n", "1")
    assert code == 0 and "\n1 random joint vector within the limits" in out
    message = one_line_error(capsys, "draw", str(path), "--orbit", "10")
    assert "got 1 value" in message and "values" not in message


def test_many_joints_are_joints(capsys):
    code, out, _ = run(capsys, "check", "puma560")
    assert code == 0 and "Puma 560: 6 joints, RRRRRR" in out


# -- a long name is shortened in the middle -------------------------------------------


def test_shortened_keeps_the_start_and_the_end():
    assert shortened("x" * SHOWN_CHARS) == "x" * SHOWN_CHARS
    text = "start" + "m" * 5000 + "end"
    short = shortened(text)
    assert len(short) == SHOWN_CHARS
    assert short.startswith("startmm") and short.endswith("mmend") and " … " in short
    assert shortened("abcdefghij", 7) == "ab … ij"  # 7 characters in all


@pytest.mark.parametrize("command", ["check", "fk", "workspace"])
def test_a_long_name_is_shortened_in_the_middle(capsys, tmp_path, command):
    name = "Begin" + "n" * 900 + "Finish"
    path = tmp_path / "long.toml"
    path.write_text(ONE_JOINT.format(name=name), encoding="utf-8")
    code, out, err = run(capsys, command, str(path))
    assert code == 0, err
    line = next(line for line in out.splitlines() if "Begin" in line)
    assert "Finish" in line and " … " in line
    assert len(line) < SHOWN_CHARS + len(str(path)) + 100


def test_json_keeps_the_whole_name(capsys, tmp_path):
    name = "Begin" + "n" * 900 + "Finish"
    path = tmp_path / "long.toml"
    path.write_text(ONE_JOINT.format(name=name), encoding="utf-8")
    code, out, _ = run(capsys, "fk", str(path), "--json")
    assert code == 0 and f'"robot": "{name}"' in out
