"""The command line under a fault campaign: too many arguments, huge ones,
and a standard error that is full or closed.

* 30,000 unknown options took argparse a minute (its time grows with the
  square of their number) and printed a 150 KB line: more than
  MAX_ARGUMENTS arguments are refused in one short line, exit 2, and every
  argument an error quotes is shortened in the middle.
* ``2>/dev/full`` turned exit 2 into 1 (the error line could not be
  written, and that failure became an internal error); with stderr closed
  (``2>&-``) Python has no sys.stderr and ``print(file=sys.stderr)`` wrote
  the error to stdout, into the CSV of ``dhsim run --csv -`` or the robot of
  ``dhsim import``. An error that cannot be written keeps its exit status
  (2 for bad input, 3 for problems ``dhsim run`` found), and nothing meant
  for stderr ever reaches stdout.

The real console script runs in a subprocess, as a user or a script runs it.
"""

from __future__ import annotations

import os
import subprocess
from dataclasses import replace

import pytest
from pty_screen import dhsim_command
from waiting import HANG

from dhsim_tui.cli.main import MAX_ARGUMENTS, SHOWN_ARGUMENT, main
from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.files.robotfile import dumps
from dhsim_tui.core.model.program import Program, Step
from dhsim_tui.core.model.text import ELLIPSIS


def dhsim(*argv: str, stderr=subprocess.PIPE, **kwargs) -> subprocess.CompletedProcess[str]:
    """The console script beside the interpreter, stdin from /dev/null."""
    return subprocess.run(
        [dhsim_command(), *argv],
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=stderr,
        text=True,
        timeout=HANG,  # a hang guard only: 30,000 options took argparse a minute
        **kwargs,
    )


def error_line(capsys, *argv: str) -> tuple[int, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    assert captured.out == ""
    lines = captured.err.splitlines()
    assert len(lines) == 1, captured.err[:2000]
    return code, lines[0]


# -- too many arguments, and long ones ----------------------------------------------------


def test_thirty_thousand_unknown_options_are_refused_in_one_short_line():
    done = dhsim("fk", "puma560", *(f"--option{i}" for i in range(30_000)))
    assert done.returncode == 2
    assert done.stdout == ""
    assert done.stderr == (
        f"dhsim: error: 30,002 arguments; a command takes at most {MAX_ARGUMENTS:,} "
        "(see 'dhsim --help')\n"
    )


def test_arguments_up_to_the_bound_are_parsed_and_one_more_is_refused(capsys):
    unknown = [f"--option{i}" for i in range(MAX_ARGUMENTS - 2)]
    code, line = error_line(capsys, "fk", "puma560", *unknown)
    # argparse's own error, the unknown options listed shortly
    assert code == 2
    assert line == (
        f"dhsim fk: error: unrecognized arguments: --option0 --option1 --option2 and "
        f"{MAX_ARGUMENTS - 5:,} more (see 'dhsim fk --help')"
    )
    code, line = error_line(capsys, "fk", "puma560", *unknown, "--one-more")
    assert code == 2
    assert f"{MAX_ARGUMENTS + 1:,} arguments; a command takes at most {MAX_ARGUMENTS:,}" in line


LONG = "x" * 3000 + "END"


@pytest.mark.parametrize(
    "argv",
    [
        ("fk", "puma560", f"--{LONG}"),  # an unknown option
        ("fk", "puma560", "extra", LONG),  # unknown positionals
        ("edit", "puma560", "--theme", LONG),  # an invalid choice (quoted by argparse)
        ("run", "puma560", "demo", "--rate", LONG),  # an invalid value
        ("workspace", "puma560", "--n", LONG),
        ("fk", LONG),  # no such robot (the core's message)
        ("check", "/" + LONG),
        ("export", "puma560", "--format", LONG),
    ],
    ids=lambda argv: " ".join(a[:12] for a in argv),
)
def test_every_argument_an_error_quotes_is_shortened(capsys, argv):
    code, line = error_line(capsys, *argv)
    assert code == 2
    assert len(line) < 2 * SHOWN_ARGUMENT + 200, line
    assert "xxx" + ELLIPSIS in line, line  # its start and its end kept
    assert "END" in line


def test_many_long_unknown_arguments_make_a_short_line(capsys):
    code, line = error_line(capsys, "check", "puma560", *([LONG] * 500))
    assert code == 2
    assert line.startswith("dhsim check: error: unrecognized arguments: xxx")
    assert line.endswith(" and 497 more (see 'dhsim check --help')")
    assert len(line) < 4 * SHOWN_ARGUMENT + 200


# -- standard error full or closed -------------------------------------------------------

#: a device every write to fails with "no space left on device"
FULL = "/dev/full"
needs_full = pytest.mark.skipif(not os.path.exists(FULL), reason="no /dev/full here")


def close_stderr() -> None:
    """Run in the child before it starts: ``2>&-``."""
    os.close(2)


@pytest.fixture
def problem_robot(tmp_path):
    """A Puma file with a program that puts Th1 on its limit: ``dhsim run`` exits 3."""
    puma, _ = load_robot("puma560")
    program = Program("limit", (Step("joint", (160, 0, 0, 0, 0, 0)), Step("wait", seconds=0.1)))
    path = tmp_path / "arm.toml"
    path.write_text(dumps(replace(puma, programs=(program,))), encoding="utf-8")
    return path


BAD_INPUT = [
    ("check", "no-such-robot"),  # the core's error
    ("--no-such-option",),  # argparse's error
    ("fk", "puma560", "--q", "1,2"),
    ("fk", "puma560", *(f"--o{i}" for i in range(MAX_ARGUMENTS))),  # too many
    ("edit", "puma560"),  # the simulator needs a terminal
]


@needs_full
@pytest.mark.parametrize("argv", BAD_INPUT, ids=lambda argv: " ".join(argv[:3]))
def test_with_stderr_full_a_usage_error_still_exits_2_and_stdout_stays_empty(argv):
    with open(FULL, "w") as full:
        done = dhsim(*argv, stderr=full)
    assert (done.returncode, done.stdout) == (2, "")


@pytest.mark.parametrize("argv", BAD_INPUT, ids=lambda argv: " ".join(argv[:3]))
def test_with_stderr_closed_a_usage_error_still_exits_2_and_never_goes_to_stdout(argv):
    done = dhsim(*argv, stderr=None, preexec_fn=close_stderr)
    assert (done.returncode, done.stdout) == (2, "")


@needs_full
def test_with_stderr_full_or_closed_run_keeps_status_3_and_stdout_holds_only_the_csv(
    problem_robot,
):
    argv = ("run", str(problem_robot), "limit", "--csv", "-")
    reference = dhsim(*argv)
    assert reference.returncode == 3
    assert "problem" in reference.stderr  # the report goes to stderr when stdout is the CSV
    csv_text = reference.stdout
    assert csv_text.startswith("time,step,move,") and "problem" not in csv_text
    with open(FULL, "w") as full:
        done = dhsim(*argv, stderr=full)
    assert (done.returncode, done.stdout) == (3, csv_text)
    done = dhsim(*argv, stderr=None, preexec_fn=close_stderr)
    assert (done.returncode, done.stdout) == (3, csv_text)


@needs_full
def test_with_stderr_closed_remarks_never_go_into_the_robot_on_stdout():
    # convert's remark goes to stderr while stdout carries the robot file
    argv = ("convert", "puma560", "--convention", "modified")
    reference = dhsim(*argv)
    assert reference.returncode == 0 and reference.stderr.strip()
    done = dhsim(*argv, stderr=None, preexec_fn=close_stderr)
    assert (done.returncode, done.stdout) == (0, reference.stdout)
    with open(FULL, "w") as full:
        done = dhsim(*argv, stderr=full)
    assert (done.returncode, done.stdout) == (0, reference.stdout)


def test_with_stdout_and_stderr_closed_the_status_is_still_2():
    def close_both() -> None:
        os.close(1)
        os.close(2)

    done = subprocess.run(
        [dhsim_command(), "check", "puma560"],
        stdin=subprocess.DEVNULL,
        timeout=HANG,
        preexec_fn=close_both,
    )
    assert done.returncode == 2
