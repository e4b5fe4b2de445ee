"""The command line by the conventions (issue 27 §6): ``ik`` without a
solution exits 3 (2 stays for bad input) and says why in JSON with
``--json``; ``check --json``; ``run --csv`` starts with its header row and
gives the units in ``--help`` and ``--json``, while ``import --program``
still reads the old files that start with a comment line; ``dhsim bogus``
is an unknown command, even in a pipe; the no-terminal message names every
command that works without one; ``--version``; shell completion."""

from __future__ import annotations

import csv
import io
import json
import shutil
import subprocess

import pytest
from pty_screen import dhsim_command
from waiting import HANG

from dhsim_tui import __version__
from dhsim_tui.cli.completion import bash_script
from dhsim_tui.cli.main import INTERACTIVE, _main_parser, _subparsers, main
from dhsim_tui.core.files.library import bundled_names, load_robot
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.motion.trajectory import sample
from dhsim_tui.core.motion.trajectory_csv import column_units, csv_text, program_from_csv

COLUMNS = "time,step,move,q1,q2,q3,q4,q5,q6,x,y,z,o,a,t,mu"
#: the comment line ``dhsim run --csv`` wrote first before the header came first
OLD_COMMENT = (
    '# dhsim trajectory: robot "Puma 560", program "demo", 20 Hz; units: time s, '
    "q1 deg, q2 deg, q3 deg, q4 deg, q5 deg, q6 deg, x y z mm, o a t deg, mu dimensionless"
)


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def dhsim(*argv: str) -> subprocess.CompletedProcess[str]:
    """The console script with stdin from /dev/null and stdout a pipe."""
    return subprocess.run(
        [dhsim_command(), *argv],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=HANG,
    )


# -- ik: no solution is exit 3 --------------------------------------------------------------


@pytest.mark.parametrize(
    "argv",
    [
        ("ik", "puma560", "--xyz", "5000,0,0"),
        ("ik", "planar2", "--xyz", "1,1,1"),
        ("ik", "puma560", "--xyz", "5000,0,0", "--oat", "0,0,0", "--all"),
    ],
)
def test_ik_without_a_solution_exits_3_with_one_line_on_stderr(capsys, argv):
    code, out, err = run(capsys, *argv)
    assert (code, out) == (3, "")
    assert err.count("\n") == 1 and err.startswith("dhsim: no solution for ")


@pytest.mark.parametrize("extra", [(), ("--all", "--oat", "0,0,0")])
def test_ik_json_without_a_solution_says_why_in_one_object(capsys, extra):
    code, out, err = run(capsys, "ik", "puma560", "--xyz", "5000,0,0", "--json", *extra)
    assert (code, err) == (3, "")
    answer = json.loads(out)
    assert answer["solved"] is False and answer["robot"] == "Puma 560"
    assert answer["units"] == "mm" and "out of reach" in answer["reason"]
    if extra:
        assert answer["solutions"] == []


def test_ik_json_with_a_solution_says_solved(capsys):
    code, out, _ = run(capsys, "ik", "puma560", "--xyz", "500,0,300", "--json")
    assert code == 0 and json.loads(out)["solved"] is True
    code, out, _ = run(capsys, "ik", "puma560", "--xyz", "500,0,300", "--all", "--json")
    assert code == 0 and json.loads(out)["solved"] is True


def test_ik_bad_input_still_exits_2(capsys):
    code, out, err = run(capsys, "ik", "puma560", "--xyz", "1,2", "--json")
    assert (code, out) == (2, "") and "--xyz: expected 3 numbers" in err
    code, out, _ = run(capsys, "ik", "--help")
    assert code == 0 and "3: no solution" in " ".join(out.split())


# -- check --json ---------------------------------------------------------------------------


def test_check_json_is_one_object_with_the_summary(capsys):
    code, out, err = run(capsys, "check", "puma560", "--json")
    assert (code, err) == (0, "")
    answer = json.loads(out)
    assert answer["ok"] is True and answer["robot"] == "Puma 560"
    assert answer["path"].endswith("puma560.toml")
    assert (answer["units"], answer["convention"], answer["joints"]) == ("mm", "standard", 6)
    assert answer["types"] == "RRRRRR" and answer["reach"] == 877.01
    assert "demo" in answer["programs"] and "qn" in answer["poses"]


def test_check_json_of_a_bad_robot_is_an_error_on_stderr(capsys):
    code, out, err = run(capsys, "check", "no/such.toml", "--json")
    assert (code, out) == (2, "") and err.startswith("dhsim: error: no/such.toml")


# -- run --csv: the header row first, the units in --help and --json -----------------------


def test_run_csv_starts_with_the_header_row(capsys):
    code, out, _ = run(capsys, "run", "puma560", "demo", "--csv", "-", "--rate", "10")
    assert code == 0
    lines = out.splitlines()
    assert lines[0] == COLUMNS
    assert not any(line.startswith("#") for line in lines)
    rows = list(csv.DictReader(io.StringIO(out)))  # what pandas.read_csv(f) does
    assert len(rows) == 80 - 3 and rows[0]["time"] == "0" and rows[-1]["move"] == "joint"


def test_the_core_csv_starts_with_the_header_row():
    robot, _ = load_robot("puma560")
    assert csv_text(sample(robot, robot.program("demo"), 5.0)).startswith(COLUMNS + "\n")


def test_run_help_gives_every_columns_unit(capsys):
    code, out, _ = run(capsys, "run", "--help")
    assert code == 0
    for words in ("time          s", "q1 ... qN", "deg (revolute)", "x, y, z", "dimensionless"):
        assert words in out
    assert "column_units" in out


def test_run_json_gives_each_columns_unit(capsys):
    code, out, _ = run(capsys, "run", "puma560", "demo", "--json")
    units = json.loads(out)["column_units"]
    assert code == 0 and ",".join(units) == COLUMNS
    assert units["time"] == "s" and units["q6"] == "deg" and units["x"] == "mm"
    assert units["o"] == "deg" and units["mu"] is None and units["move"] is None
    stanford, _ = load_robot("stanford")  # RRPRRR: the prismatic joint in the robot's unit
    units = column_units(stanford)
    assert (units["q2"], units["q3"], units["z"]) == ("deg", stanford.units, stanford.units)


def _demo_csv(capsys) -> str:
    code, out, _ = run(capsys, "run", "puma560", "demo", "--csv", "-", "--rate", "20")
    assert code == 0
    return out


def test_import_program_reads_the_new_csv_and_the_old_one_with_the_comment_first(capsys, tmp_path):
    new = _demo_csv(capsys)
    (tmp_path / "new.csv").write_text(new, encoding="utf-8")
    (tmp_path / "old.csv").write_text(f"{OLD_COMMENT}\n{new}", encoding="utf-8")
    programs = []
    for name in ("new", "old"):
        code, out, err = run(
            capsys, "import", "--program", str(tmp_path / f"{name}.csv"), "puma560"
        )
        assert code == 0, err
        programs.append(out.split(f"\n{name} = [\n", 1)[1].split("\n]", 1)[0])
    assert programs[0] == programs[1] and programs[0].count("move =") == 4


def test_an_old_comment_with_other_units_is_still_refused(capsys):
    robot, _ = load_robot("puma560")
    new = _demo_csv(capsys)
    with pytest.raises(DhsimError, match="q2 is in rad in the file"):
        program_from_csv(robot, OLD_COMMENT.replace("q2 deg", "q2 rad") + "\n" + new, "x")


def test_a_units_comment_after_the_header_is_checked_too(capsys):
    robot, _ = load_robot("puma560")
    header, rest = _demo_csv(capsys).split("\n", 1)
    text = f"{header}\n{OLD_COMMENT.replace('q2 deg', 'q2 rad')}\n{rest}"
    with pytest.raises(DhsimError, match="q2 is in rad in the file"):
        program_from_csv(robot, text, "x")
    assert program_from_csv(robot, f"{header}\n{OLD_COMMENT}\n{rest}", "x").steps


# -- dhsim bogus, and the message without a terminal ----------------------------------------


def test_an_unknown_command_is_said_in_a_pipe():
    result = dhsim("bogus")
    assert (result.returncode, result.stdout) == (2, "")
    assert result.stderr.startswith("dhsim: error: unknown command 'bogus'")
    assert result.stderr.count("\n") == 1 and "the commands are fk, ik" in result.stderr


def test_an_unknown_command_close_to_one_says_which(capsys):
    code, out, err = run(capsys, "rnu", "puma560")
    assert (code, out) == (2, "")
    assert "unknown command 'rnu': did you mean 'run'?" in err


@pytest.mark.parametrize("argv", [["puma560"], ["./no/such.toml"], []])
def test_a_robot_or_a_path_is_not_an_unknown_command(argv):
    result = dhsim(*argv)
    assert result.returncode == 2 and "unknown command" not in result.stderr
    assert "needs an interactive terminal" in result.stderr


def test_a_file_named_like_a_word_opens_as_a_robot(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "arm").write_text((load_robot("puma560")[1]).read_text(), encoding="utf-8")
    result = dhsim("arm")
    assert "unknown command" not in result.stderr


def test_the_no_terminal_message_names_every_command_that_works_without_one():
    result = dhsim("puma560")
    message = result.stderr.strip()
    assert result.returncode == 2 and message.endswith("work without one")
    named = message.split("; ", 1)[1].removesuffix(" work without one")
    listed = named.replace(" and ", ", ").split(", ")
    subs = _subparsers()
    expected = [n for n, p in subs.items() if p.get_default("func") not in INTERACTIVE]
    assert listed == expected and "run" in listed and "edit" not in listed


# -- --version ------------------------------------------------------------------------------


def test_version_prints_the_packages_version():
    result = dhsim("--version")
    assert (result.returncode, result.stdout, result.stderr) == (0, f"dhsim {__version__}\n", "")


# -- shell completion -----------------------------------------------------------------------


def _bash_complete(script: str, *words: str) -> list[str]:
    """What the script's completion function offers for the command line ``words``
    (the last being the word under the cursor), in a fresh bash."""
    probe = (
        'eval "$DHSIM_COMPLETION"\n'
        'COMP_WORDS=("$@"); COMP_CWORD=$(( $# - 1 )); COMPREPLY=()\n'
        "_dhsim\n"
        'printf "%s\\n" "${COMPREPLY[@]}"\n'
    )
    result = subprocess.run(
        ["bash", "-c", probe, "bash", *words],
        env={"PATH": "/usr/bin:/bin", "DHSIM_COMPLETION": script},
        capture_output=True,
        text=True,
        timeout=HANG,
    )
    assert result.returncode == 0 and result.stderr == "", result.stderr
    return [line for line in result.stdout.splitlines() if line]


needs_bash = pytest.mark.skipif(shutil.which("bash") is None, reason="no bash")


@needs_bash
def test_bash_completion_completes_ru_to_run():
    result = dhsim("--completion", "bash")
    assert (result.returncode, result.stderr) == (0, "")
    assert "complete -o filenames -F _dhsim dhsim" in result.stdout
    assert _bash_complete(result.stdout, "dhsim", "ru") == ["run"]


@needs_bash
def test_bash_completion_knows_the_options_the_choices_and_the_robots(tmp_path):
    script = bash_script(_subparsers(), _main_parser(), bundled_names())
    assert _bash_complete(script, "dhsim", "run", "puma560", "demo", "--c") == ["--csv"]
    assert _bash_complete(script, "dhsim", "draw", "puma560", "--view", "") == [
        "top",
        "front",
        "side",
        "3d",
        "all",
    ]
    assert _bash_complete(script, "dhsim", "--theme", "a") == ["ansi"]
    assert _bash_complete(script, "dhsim", "check", "puma560", "--") == ["--help", "--json"]
    assert "puma560" in _bash_complete(script, "dhsim", "fk", "pu")
    assert _bash_complete(script, "dhsim", "--completion", "z") == ["zsh"]
    assert _bash_complete(script, "dhsim", "ik", "puma560", "--xyz", "") == []


def test_every_option_of_every_parser_is_in_both_scripts():
    subs = _subparsers()
    for shell in ("bash", "zsh"):
        code = main(["--completion", shell])
        assert code == 0
    for shell, script in (
        ("bash", bash_script(subs, _main_parser(), bundled_names())),
        ("zsh", _zsh(subs)),
    ):
        for name, parser in subs.items():
            assert name in script, (shell, name)
            for action in parser._actions:
                for option in action.option_strings:
                    assert option in script, (shell, name, option)
        assert "--completion" in script and "--version" in script


def _zsh(subs) -> str:
    from dhsim_tui.cli.completion import zsh_script

    return zsh_script(subs, _main_parser(), bundled_names())


def test_the_zsh_script_is_a_compdef_function_with_every_command():
    script = _zsh(_subparsers())
    assert script.startswith("#compdef dhsim\n")
    assert "'run:Play a robot" in script and "'(-o --output)'{-o,--output}" in script
    assert "'--view=[" in script and ":(top front side 3d all)'" in script
    assert "compdef _dhsim dhsim" in script
    quotes = sum(line.count("'") for line in script.splitlines() if not line.startswith("#"))
    assert quotes % 2 == 0  # every single quote closed


@needs_bash
def test_the_zsh_script_is_at_least_shell_syntax():
    # no zsh on the test machine: bash -n checks the quoting and the braces
    result = subprocess.run(
        ["bash", "-n"], input=_zsh(_subparsers()), capture_output=True, text=True, timeout=HANG
    )
    assert result.returncode == 0, result.stderr


@pytest.mark.parametrize(
    ("argv", "got"), [(["--completion"], "got none"), (["--completion", "fish"], "got 'fish'")]
)
def test_completion_needs_one_known_shell(capsys, argv, got):
    code, out, err = run(capsys, *argv)
    assert (code, out) == (2, "")
    assert err.startswith("dhsim: error: --completion: give one shell, bash or zsh") and got in err
