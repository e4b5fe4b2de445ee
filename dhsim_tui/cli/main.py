"""The ``dhsim`` command: a thin shell over the core.

``fk``, ``ik``, ``check`` and ``list`` never import textual (they are used in
scripts and must start fast); only opening the simulator does, and only when
stdin and stdout are a terminal. Every bad input ends as one line on stderr
and exit status 2, never a traceback; an unexpected error as one line and
exit status 1. Whatever the line quotes from the user or a file is passed
through :func:`printable`, so no control character reaches the terminal, and
every argument it quotes is shortened in the middle past
:data:`SHOWN_ARGUMENT` characters. More than :data:`MAX_ARGUMENTS`
arguments are refused before argparse sees them (its time grows with the
square of their number: 30,000 took a minute). Output that cannot be
written (a full disk, standard output closed) is one line and status 2 as
well; a reader that stops early (``dhsim list | head -1``) is not an error.
Errors go to stderr only (:mod:`dhsim_tui.cli.streams`): with stderr closed
or full, the line is lost but the exit status is kept, and nothing meant
for stderr lands on stdout. An option given twice is refused, not overridden.
"""

from __future__ import annotations

import argparse
import contextlib
import difflib
import os
import re
import sys
from collections.abc import Sequence

import numpy as np

from dhsim_tui import __version__
from dhsim_tui.cli.draw import subparsers as draw_subparsers
from dhsim_tui.cli.files import subparsers as files_subparsers
from dhsim_tui.cli.kinematics import VALUE_OPTIONS
from dhsim_tui.cli.kinematics import subparsers as kinematics_subparsers
from dhsim_tui.cli.library import cmd_list, new_target, note_which, opened_notice
from dhsim_tui.cli.run import subparsers as run_subparsers
from dhsim_tui.cli.streams import hold_closed_stderr, silence, to_stderr
from dhsim_tui.cli.workspace import subparsers as workspace_subparsers
from dhsim_tui.core.files.library import DEFAULT_ROBOT, describe, load_robot, resolve
from dhsim_tui.core.files.robotfile import load_with_stamp
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.text import SHOWN_CHARS, printable, shortened
from dhsim_tui.terminal.locale_env import original_environ, wants_ascii

EXIT_USAGE = 2
EXIT_INTERNAL = 1
EXIT_INTERRUPTED = 130
#: the most arguments one command line may have: a command takes fewer than
#: 20, and argparse's time grows with the square of their number
MAX_ARGUMENTS = 1_000
#: the most characters of one argument an error quotes (its start and end):
#: as many as of a name from a file
SHOWN_ARGUMENT = SHOWN_CHARS
#: the unrecognised arguments an error lists before "and N more"
LISTED_ARGUMENTS = 3
#: the longest error line (a last resort: arguments are shortened before)
MAX_ERROR_CHARS = 1_000
NEEDS_TERMINAL = "dhsim: the simulator needs an interactive terminal (over SSH use ssh -t)"


class UsageError(Exception):
    """A command line argparse could not accept."""


class OutputError(Exception):
    """Standard output cannot be written; the message says why."""


class _StoreOnce(argparse._StoreAction):
    """An option that takes a value refuses a second one: ``--q 1,2 --q 3,4``
    would otherwise keep the last without a word."""

    def __call__(self, parser, namespace, values, option_string=None) -> None:
        given = vars(namespace).setdefault("_options_given", set())
        if option_string is not None and self.dest in given:
            raise argparse.ArgumentError(self, "given more than once; give it once")
        given.add(self.dest)
        super().__call__(parser, namespace, values, option_string)


class _Parser(argparse.ArgumentParser):
    """Every dhsim parser: errors in one line, options with a value given once."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self.register("action", None, _StoreOnce)
        self.register("action", "store", _StoreOnce)

    def parse_known_args(self, args=None, namespace=None):
        self._given = list(sys.argv[1:] if args is None else args)
        return super().parse_known_args(self._given, namespace)

    def parse_args(self, args=None, namespace=None):  # the unknown ones listed shortened
        namespace, extras = self.parse_known_args(args, namespace)
        if extras:
            self.error(f"unrecognized arguments: {_listed(extras)}")
        return namespace

    def error(self, message: str):  # one line, no usage dump
        message = shortened_arguments(message, getattr(self, "_given", ()))
        raise UsageError(f"{self.prog}: error: {message} (see '{self.prog} --help')")


def _listed(arguments: Sequence[str]) -> str:
    """``--a --b --c and 29,997 more``: the first few, each shortened."""
    shown = " ".join(shortened(a, SHOWN_ARGUMENT) for a in arguments[:LISTED_ARGUMENTS])
    more = len(arguments) - LISTED_ARGUMENTS
    return f"{shown} and {more:,} more" if more > 0 else shown


def shortened_arguments(message: str, arguments: Sequence[str]) -> str:
    """``message`` with every argument of more than :data:`SHOWN_ARGUMENT`
    characters it quotes (as given, in quotes, or escaped) shortened in the
    middle: ``'xxxxxxxxxxxxxxxxxxxxxxxxxxxx … xxxxxxxxxxxxxxxxxxxxxxxxxxxxx'``."""
    for argument in sorted({a for a in arguments if len(a) > SHOWN_ARGUMENT}, key=len)[::-1]:
        short = shortened(argument, SHOWN_ARGUMENT)
        for given, shown in (
            (repr(argument), repr(short)),
            (printable(argument), printable(short)),
            (argument, short),
        ):
            if len(given) > len(shown) and given in message:
                message = message.replace(given, shown)
    return message


class _Output:
    """``sys.stdout`` while a command runs: a write or flush that fails
    (other than for a closed pipe) is an :class:`OutputError` saying why."""

    def __init__(self, stream) -> None:
        self.stream = stream

    def write(self, text: str) -> int:
        try:
            return self.stream.write(text)
        except BrokenPipeError:
            raise
        except (OSError, ValueError) as exc:
            raise OutputError(_reason(exc)) from None

    def flush(self) -> None:
        try:
            self.stream.flush()
        except BrokenPipeError:
            raise
        except (OSError, ValueError) as exc:
            raise OutputError(_reason(exc)) from None

    def __getattr__(self, name: str):
        return getattr(self.stream, name)


def _reason(exc: BaseException) -> str:
    """``no space left on device``: the system's words, as part of a sentence."""
    text = getattr(exc, "strerror", None) or str(exc) or type(exc).__name__
    return printable(text[:1].lower() + text[1:])


def _glue_negative_values(argv: list[str]) -> list[str]:
    """``--q -10,20`` -> ``--q=-10,20`` (argparse would take -10,20 for an option)."""
    out: list[str] = []
    skip = False
    for i, arg in enumerate(argv):
        if skip:
            skip = False
            continue
        following = argv[i + 1] if i + 1 < len(argv) else ""
        if arg in VALUE_OPTIONS and following[:1] == "-" and following[1:2] in "0123456789.":
            out.append(f"{arg}={argv[i + 1]}")
            skip = True
        else:
            out.append(arg)
    return out


def cmd_check(args: argparse.Namespace) -> int:
    robot, path = load_robot(args.robot)
    if args.json:
        print(check_json(robot, path))
    else:
        print(printable(f"ok  {describe(robot)}  ({path})"))
    return 0


def check_json(robot, path) -> str:
    """``dhsim check --json``: the robot's summary as one JSON object (the
    reach as ``check`` shows it, to the unit's decimals)."""
    import json

    from dhsim_tui.core.analysis.workspace import arm_reach
    from dhsim_tui.core.model.robot import LENGTH_DECIMALS

    return json.dumps(
        {
            "ok": True,
            "robot": robot.name,
            "path": str(path),
            "units": robot.units,
            "convention": robot.convention,
            "joints": robot.dof,
            "types": robot.type_string,
            "reach": round(arm_reach(robot), LENGTH_DECIMALS[robot.units]) + 0.0,
            "poses": list(robot.pose_names),
            "programs": list(robot.program_names),
        }
    )


def has_terminal() -> bool:
    """Both stdin and stdout are a terminal (the simulator reads keys and draws)."""
    for stream in (sys.stdin, sys.stdout):
        try:
            if stream is None or not os.isatty(stream.fileno()):
                return False
        except (AttributeError, OSError, ValueError):  # closed, or not a real file
            return False
    return True


def _open(argument: str | None):
    """The robot, its file and the stamp of the very bytes read (a save later
    refuses to overwrite a change made on disk since then)."""
    path = resolve(argument if argument is not None else DEFAULT_ROBOT)
    robot, stamp = load_with_stamp(path)
    return robot, path, stamp


def ascii_screen(args: argparse.Namespace) -> bool:
    """Whether the simulator draws in 7-bit ASCII: ``--ascii`` or ``--unicode``
    if given, else the locale the process was started with and TERM.
    In ASCII mode whatever is printed after the app ends is ASCII as well
    (backslash escapes for what has no ASCII form)."""
    ascii = wants_ascii(original_environ(), force=args.force_ascii)
    if ascii:
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(AttributeError, ValueError, OSError):
                stream.flush()
                stream.reconfigure(encoding="ascii", errors="backslashreplace")  # type: ignore[union-attr]
    return ascii


def cmd_run(args: argparse.Namespace) -> int:
    robot, path, stamp = _open(args.robot)  # a bad robot is reported before any UI starts
    from dhsim_tui.tui.app import run_app  # textual loads only for the simulator

    return run_app(
        robot,
        path,
        args.renderer,
        stamp=stamp,
        ascii=ascii_screen(args),
        theme=args.theme,
        notice=opened_notice(args.robot),
    )


def cmd_edit(args: argparse.Namespace) -> int:
    robot, path, stamp = _open(args.robot)
    from dhsim_tui.tui.app import run_app

    return run_app(
        robot,
        path,
        start="edit",
        stamp=stamp,
        ascii=ascii_screen(args),
        theme=args.theme,
        notice=opened_notice(args.robot),
    )


def cmd_new(args: argparse.Namespace) -> int:
    from dhsim_tui.core.model.editing import new_robot

    robot = new_robot(args.name.strip() or "new robot")  # checked before any UI starts
    target = new_target(args.output)  # None: the save dialog offers the user library
    from dhsim_tui.tui.app import run_app

    return run_app(
        robot, None, start="new", ascii=ascii_screen(args), theme=args.theme, new_target=target
    )


def _add_charset_options(parser: argparse.ArgumentParser) -> None:
    """``--ascii`` / ``--unicode``: override what the locale and TERM say;
    ``--theme``: the colours."""
    parser.add_argument(
        "--theme",
        choices=("dark", "light", "ansi"),
        default="dark",
        help="colours: dark (default), light, or ansi (the terminal's own palette)",
    )
    group = parser.add_mutually_exclusive_group()
    group.add_argument(
        "--ascii",
        dest="force_ascii",
        action="store_const",
        const=True,
        default=None,
        help="draw only 7-bit ASCII (default when the locale is not UTF-8, or TERM=linux)",
    )
    group.add_argument(
        "--unicode",
        dest="force_ascii",
        action="store_const",
        const=False,
        help="draw with Unicode box drawing and symbols whatever the locale says",
    )


def _subparsers() -> dict[str, _Parser]:
    check = _Parser(prog="dhsim check", description="Validate a robot and summarise it.")
    check.add_argument("robot", help="a robot file or a bundled robot's name")
    check.add_argument("--json", action="store_true", help="print one JSON object")
    check.set_defaults(func=cmd_check)
    listing = _Parser(
        prog="dhsim list",
        description="List your robots (the user library, with their paths) and the bundled ones.",
    )
    listing.add_argument(
        "--json", action="store_true", help='one JSON object: "yours" and "bundled"'
    )
    listing.set_defaults(func=cmd_list)
    edit = _Parser(prog="dhsim edit", description="Open a robot in the table editor.")
    edit.add_argument("robot", help="a robot file or a robot's name (yours first, then bundled)")
    _add_charset_options(edit)
    edit.set_defaults(func=cmd_edit)
    new = _Parser(prog="dhsim new", description="Start a new robot in the table editor.")
    new.add_argument("name", nargs="?", default="new robot", help="the robot's name")
    new.add_argument(
        "-o",
        "--output",
        default=None,
        metavar="FILE.toml",
        help="where saving puts it (default: your robot library, see 'dhsim list')",
    )
    _add_charset_options(new)
    new.set_defaults(func=cmd_new)
    return {
        **kinematics_subparsers(_Parser),
        "check": check,
        "list": listing,
        "edit": edit,
        "new": new,
        **files_subparsers(_Parser),
        **workspace_subparsers(_Parser),
        **draw_subparsers(_Parser),
        **run_subparsers(_Parser),
    }


MAIN_HELP = """\
usage: dhsim [ROBOT] [--renderer plotext|braille] [--ascii | --unicode]
             [--theme dark|light|ansi]
                                 open the simulator (default: the bundled Puma 560)
       dhsim fk ROBOT [--q V1,V2,...] [--pose NAME] [--json]
       dhsim ik ROBOT --xyz X,Y,Z [--oat O,A,T] [--from V1,V2,...] [--all] [--json]
       dhsim check ROBOT [--json]
       dhsim list [--json]
                                 your robots (with their paths), then the bundled ones
       dhsim import FILE.urdf|FILE.csv [--tip LINK] [--base LINK]
                    [--convention standard|modified] [--units mm|cm|m|in] [-o OUT.toml]
       dhsim export ROBOT --format urdf|csv|json [-o FILE]
       dhsim convert ROBOT --convention standard|modified [-o FILE.toml]
       dhsim workspace ROBOT [--n N] [--seed S] [--json]
                                 where the tool can go: bounding box and reach
       dhsim draw ROBOT [--q V1,V2,...|--pose NAME] [--view top|front|side|3d|all]
                  [--size WxH] [--fit] [--frames all|ends|none] [--orbit AZ,EL]
                  [-o FILE.svg|FILE.txt]
                                 the views as a picture for a report
       dhsim run ROBOT PROGRAM [--rate HZ] [--from V1,V2,...|POSE]
                 [--csv FILE [--force]] [--json | --plot]
                                 play a program and check its path (exit 3: problems)
       dhsim edit ROBOT [--ascii | --unicode]
                                 the table editor
       dhsim new [NAME] [-o FILE.toml] [--ascii | --unicode]
                                 a new robot in the table editor, saved in your
                                 robot library (or FILE.toml)

ROBOT is a robot file (.toml) or a robot's name, e.g. puma560: your robot
library ($XDG_DATA_HOME/dhsim/robots, else ~/.local/share/dhsim/robots) is
looked in first, then the bundled robots.
The simulator draws in 7-bit ASCII when the locale (LC_ALL, LC_CTYPE, LANG)
is not UTF-8 or TERM=linux; --ascii and --unicode decide instead.
--theme ansi uses the terminal's own colour palette.
Run 'dhsim COMMAND --help' for a command's options.
dhsim --version prints the version; dhsim --completion bash|zsh prints a
shell completion script (see the README)."""


def _main_parser() -> _Parser:
    parser = _Parser(prog="dhsim", add_help=False)
    parser.add_argument("robot", nargs="?", default=None)
    parser.add_argument("--renderer", choices=("plotext", "braille"), default="plotext")
    _add_charset_options(parser)
    parser.set_defaults(func=cmd_run)
    return parser


#: the commands that open the simulator: they need a terminal
INTERACTIVE = (cmd_run, cmd_edit, cmd_new)


def main(argv: Sequence[str] | None = None) -> int:
    args_list = list(sys.argv[1:] if argv is None else argv)
    hold_closed_stderr()
    _escape_unencodable(sys.stdout)
    _escape_unencodable(sys.stderr)
    if sys.stdout is None:  # started with descriptor 1 closed (`dhsim ... >&-`)
        to_stderr("dhsim: cannot write the output: standard output is closed")
        return EXIT_USAGE
    stdout = sys.stdout
    sys.stdout = _Output(stdout)  # type: ignore[assignment]
    try:
        return _run(args_list, stdout)
    finally:
        if isinstance(sys.stdout, _Output):
            sys.stdout = sys.stdout.stream


def _command(args_list: list[str], stdout) -> int:
    """Parse the command line and run the command; its exit status."""
    if len(args_list) > MAX_ARGUMENTS:
        raise UsageError(
            f"dhsim: error: {len(args_list):,} arguments; a command takes at most "
            f"{MAX_ARGUMENTS:,} (see 'dhsim --help')"
        )
    if args_list and args_list[0] in ("-h", "--help"):
        print(MAIN_HELP)
        return 0
    if args_list and args_list[0] == "--version":
        print(f"dhsim {__version__}")
        return 0
    subs = _subparsers()
    if args_list and args_list[0] == "--completion":
        print(completion_script(args_list[1:], subs))
        return 0
    try:
        if args_list and args_list[0] in subs:
            parser = subs[args_list[0]]
            args = parser.parse_args(_glue_negative_values(args_list[1:]))
        else:
            _refuse_unknown_command(args_list[0] if args_list else None, subs)
            args = _main_parser().parse_args(args_list)
            _refuse_unknown_command(args.robot, subs)
    except SystemExit as exc:  # argparse after printing a command's --help
        return exc.code if isinstance(exc.code, int) else 0
    if args.func in INTERACTIVE:
        sys.stdout = stdout  # the simulator's terminal, as it was given
        if not has_terminal():
            to_stderr(needs_terminal(subs))
            return EXIT_USAGE
    else:  # the simulator says it on its status line; here stdout is data
        note_which(getattr(args, "robot", None))
    with np.errstate(all="ignore"):  # a result that lost precision is checked, not warned
        return args.func(args)


def needs_terminal(subs: dict[str, _Parser]) -> str:
    """What ``dhsim`` says without a terminal: every command that works without one."""
    names = [name for name, parser in subs.items() if parser.get_default("func") not in INTERACTIVE]
    listed = ", ".join(names[:-1]) + f" and {names[-1]}" if len(names) > 1 else "".join(names)
    return f"{NEEDS_TERMINAL}; {listed} work without one"


def _refuse_unknown_command(word: str | None, subs: dict[str, _Parser]) -> None:
    """``dhsim bogus``: a word that is neither a command, a file nor a robot's
    name is an unknown command, said before the simulator looks for a
    terminal (so in a pipe as well)."""
    if word is None or not re.fullmatch(r"[A-Za-z][A-Za-z0-9_-]*", word):
        return  # a path, a name with a dot: the robot's own error says what is wrong
    try:
        resolve(word)
        return
    except DhsimError:
        pass
    close = difflib.get_close_matches(word, list(subs), n=1)
    hint = f"did you mean '{close[0]}'? " if close else ""
    commands = ", ".join(subs)
    raise UsageError(
        f"dhsim: error: unknown command '{word}': {hint}the commands are {commands}; "
        "a robot to open is a robot file (.toml) or a robot's name (see 'dhsim --help')"
    )


def completion_script(args: Sequence[str], subs: dict[str, _Parser]) -> str:
    """``dhsim --completion bash|zsh``: the script, from the parsers' own options."""
    from dhsim_tui.cli.completion import SHELLS, script
    from dhsim_tui.core.files.library import bundled_names

    if len(args) != 1 or args[0] not in SHELLS:
        given = f"got {' '.join(map(repr, args))}" if args else "got none"
        raise UsageError(
            f"dhsim: error: --completion: give one shell, {' or '.join(SHELLS)} ({given}) "
            "(see 'dhsim --help')"
        )
    return script(args[0], subs, _main_parser(), bundled_names())


def _run(args_list: list[str], stdout) -> int:
    """Run one command; every failure ends here as one line and a status."""
    try:
        status = _command(args_list, stdout)
        sys.stdout.flush()  # a closed pipe or a full disk shows here, not at exit
        return status
    except UsageError as exc:
        to_stderr(_error_line(str(exc), args_list))
        return EXIT_USAGE
    except DhsimError as exc:
        to_stderr(_error_line(f"dhsim: error: {exc}", args_list))
        return EXIT_USAGE
    except KeyboardInterrupt:
        return EXIT_INTERRUPTED
    except BrokenPipeError:  # e.g. `dhsim list | head -1`
        _silence_stdout()
        return 0
    except OutputError as exc:  # e.g. `dhsim fk puma560 > /dev/full`
        _silence_stdout()  # what is still buffered goes nowhere at exit, quietly
        to_stderr(f"dhsim: cannot write the output: {exc}")
        return EXIT_USAGE
    except Exception as exc:  # the last resort: one line and a failure status
        to_stderr(_error_line(f"dhsim: internal error: {type(exc).__name__}: {exc}", args_list))
        return EXIT_INTERNAL


def _error_line(message: str, args_list: Sequence[str]) -> str:
    """The line an error prints: the arguments it quotes shortened, control
    characters escaped, and never more than :data:`MAX_ERROR_CHARS` characters."""
    return printable(shortened(shortened_arguments(message, args_list), MAX_ERROR_CHARS))


def _escape_unencodable(stream: object) -> None:
    """Text the terminal's encoding cannot show (a C locale and a name in
    Chinese) is written as backslash escapes instead of raising an error."""
    with contextlib.suppress(AttributeError, ValueError, OSError):
        stream.reconfigure(errors="backslashreplace")  # type: ignore[attr-defined]


def _silence_stdout() -> None:
    """After a closed pipe, send what Python still flushes at exit nowhere."""
    silence(sys.stdout)
