"""``dhsim --completion bash|zsh``: a shell completion script on stdout.

The scripts are written here by hand (no completion library), from what
the parsers define: the commands, each command's options, the choices an
option takes, and which options take a file. A robot argument completes to
the bundled robots' names and to files. Install one with::

    eval "$(dhsim --completion bash)"            # in ~/.bashrc
    source <(dhsim --completion zsh)             # in ~/.zshrc, after compinit

Nothing here imports textual: printing a script starts as fast as ``dhsim fk``.
"""

from __future__ import annotations

import argparse
import re
from collections.abc import Mapping, Sequence

#: the shells a script is written for
SHELLS = ("bash", "zsh")
#: options of the bare ``dhsim`` that its parser does not define (main.py reads them first)
TOP_OPTIONS = (
    ("--help", "show the help"),
    ("--version", "print the version"),
    ("--completion", "print a shell completion script"),
)
#: the options whose value is a file name
FILE_DESTS = ("output", "csv")
#: the positional arguments that are a file name (a robot is a file or a bundled name)
FILE_POSITIONALS = ("file",)
ROBOT_POSITIONALS = ("robot",)


def script(shell: str, commands: Mapping[str, argparse.ArgumentParser], main, robots) -> str:
    """The completion script for ``shell`` (one of :data:`SHELLS`)."""
    if shell == "bash":
        return bash_script(commands, main, robots)
    return zsh_script(commands, main, robots)


def _options(parser: argparse.ArgumentParser) -> list[argparse.Action]:
    return [action for action in parser._actions if action.option_strings]


def _positionals(parser: argparse.ArgumentParser) -> list[argparse.Action]:
    return [action for action in parser._actions if not action.option_strings]


def _takes_value(action: argparse.Action) -> bool:
    return action.nargs != 0


def _is_file(action: argparse.Action) -> bool:
    return action.dest in FILE_DESTS or action.metavar == "FILE"


def _top_options(main: argparse.ArgumentParser) -> list[str]:
    words = [name for name, _ in TOP_OPTIONS]
    return words + [o for action in _options(main) for o in action.option_strings]


# -- bash ---------------------------------------------------------------------------------


def bash_script(
    commands: Mapping[str, argparse.ArgumentParser],
    main: argparse.ArgumentParser,
    robots: Sequence[str],
) -> str:
    values: list[str] = ['        ":--completion") _dhsim_add -W "bash zsh"; return ;;']
    option_lists: list[str] = []
    for name, parser in [("", main), *commands.items()]:
        for action in _options(parser):
            if not _takes_value(action):
                continue
            keys = "|".join(f'"{name}:{option}"' for option in action.option_strings)
            if action.choices:
                reply = f'_dhsim_add -W "{" ".join(map(str, action.choices))}"'
            elif _is_file(action):
                reply = "_dhsim_add -f"
            else:
                reply = ":"  # a value to type: nothing to offer
            values.append(f"        {keys}) {reply}; return ;;")
        if name:
            words = ["--help", *(o for a in _options(parser) for o in a.option_strings)]
            words = list(dict.fromkeys(w for w in words if w != "-h"))
            option_lists.append(f'        {name}) opts="{" ".join(words)}" ;;')
    top = " ".join(dict.fromkeys(_top_options(main)))
    lines = [
        '# dhsim completion for bash: eval "$(dhsim --completion bash)" (e.g. in ~/.bashrc)',
        '_dhsim_add() {  # the matches of compgen "$@" for $cur, one a line, added to COMPREPLY',
        "    local line",
        '    while IFS= read -r line; do COMPREPLY+=("$line"); done < <(compgen "$@" -- "$cur")',
        "}",
        "",
        "_dhsim() {",
        "    local cur prev cmd opts",
        "    COMPREPLY=()",
        '    cur="${COMP_WORDS[COMP_CWORD]}"',
        '    prev=""',
        '    (( COMP_CWORD > 0 )) && prev="${COMP_WORDS[COMP_CWORD-1]}"',
        '    cmd=""',
        "    if (( COMP_CWORD > 1 )); then",
        '        case "${COMP_WORDS[1]}" in',
        f'            {"|".join(commands)}) cmd="${{COMP_WORDS[1]}}" ;;',
        "        esac",
        "    fi",
        '    case "$cmd:$prev" in',
        *values,
        "    esac",
        '    case "$cmd" in',
        *option_lists,
        f'        *) opts="{top}" ;;',
        "    esac",
        '    if [[ "$cur" == -* ]]; then',
        '        _dhsim_add -W "$opts"',
        "    elif (( COMP_CWORD == 1 )); then",
        f'        _dhsim_add -W "{" ".join(commands)} {" ".join(robots)}"',
        "        _dhsim_add -f",
        "    else",
        f'        _dhsim_add -W "{" ".join(robots)}"',
        "        _dhsim_add -f",
        "    fi",
        "}",
        "",
        "complete -o filenames -F _dhsim dhsim",
    ]
    return "\n".join(lines)


# -- zsh ----------------------------------------------------------------------------------


def _zsh_text(text: str | None) -> str:
    """Help text safe inside a single-quoted _arguments spec's brackets
    (or a _describe item): one line, no brackets, no colons, quotes escaped."""
    text = re.sub(r"\s+", " ", text or "").strip()
    text = text.replace("[", "(").replace("]", ")").replace(": ", " - ").replace(":", " ")
    return text.replace("'", "'\\''")


def _summary(parser: argparse.ArgumentParser) -> str:
    """A command's description up to its first full stop or colon."""
    return re.split(r"\. |: |\.$", parser.description or "", maxsplit=1)[0]


def _zsh_option(action: argparse.Action) -> str:
    help_text = _zsh_text(action.help or action.dest)
    names = action.option_strings
    value = ""
    if _takes_value(action):
        label = _zsh_text(action.metavar or action.dest).replace(" ", "_")
        if action.choices:
            value = f":{label}:({' '.join(map(str, action.choices))})"
        elif _is_file(action):
            value = f":{label}:_files"
        else:
            value = f":{label}: "
    if len(names) == 1:
        equals = "=" if value else ""
        return f"'{names[0]}{equals}[{help_text}]{value}'"
    exclusive = " ".join(names)
    return f"'({exclusive})'{{{','.join(names)}}}'[{help_text}]{value}'"


def _zsh_positional(number: int, action: argparse.Action) -> str:
    optional = ":" if action.nargs == "?" else ""
    label = _zsh_text(action.dest)
    if action.dest in ROBOT_POSITIONALS:
        what = "_dhsim_robots"
    elif action.dest in FILE_POSITIONALS:
        what = "_files"
    else:
        what = " "
    return f"'{number}:{optional}{label}:{what}'"


def _zsh_arguments(parser: argparse.ArgumentParser, indent: str) -> str:
    specs = [_zsh_option(a) for a in _options(parser)]
    specs += [_zsh_positional(n, a) for n, a in enumerate(_positionals(parser), start=1)]
    return f"_arguments -s \\\n{indent}    " + f" \\\n{indent}    ".join(specs)


def zsh_script(
    commands: Mapping[str, argparse.ArgumentParser],
    main: argparse.ArgumentParser,
    robots: Sequence[str],
) -> str:
    described = [
        f"        '{name}:{_zsh_text(_summary(parser))}'" for name, parser in commands.items()
    ]
    top = [f"'(- *)--{name[2:]}[{text}]'" for name, text in TOP_OPTIONS[:2]]
    top.append(f"'(- *)--completion[{TOP_OPTIONS[2][1]}]:shell:({' '.join(SHELLS)})'")
    top += [_zsh_option(a) for a in _options(main)]
    cases = [
        f"                {name})\n                    {_zsh_arguments(parser, ' ' * 20)}\n"
        "                    ;;"
        for name, parser in commands.items()
    ]
    lines = [
        "#compdef dhsim",
        "# dhsim completion for zsh: source <(dhsim --completion zsh) in ~/.zshrc after",
        "# compinit, or dhsim --completion zsh > _dhsim in a folder of $fpath",
        "",
        "_dhsim_robots() {",
        f"    _alternative 'robots:bundled robot:({' '.join(robots)})' 'files:robot file:_files'",
        "}",
        "",
        "_dhsim() {",
        '    local curcontext="$curcontext" state line',
        "    typeset -A opt_args",
        "    local -a commands=(",
        *described,
        "    )",
        "    _arguments -C -s \\",
        *(f"        {spec} \\" for spec in top),
        "        '1: :->first' \\",
        "        '*:: :->args'",
        "    case $state in",
        "        first)",
        "            _describe -t commands 'dhsim command' commands",
        "            _dhsim_robots",
        "            ;;",
        "        args)",
        "            case $line[1] in",
        *cases,
        "            esac",
        "            ;;",
        "    esac",
        "}",
        "",
        'if [[ "$funcstack[1]" == _dhsim ]]; then  # autoloaded from $fpath',
        '    _dhsim "$@"',
        "else  # sourced: source <(dhsim --completion zsh)",
        "    compdef _dhsim dhsim",
        "fi",
    ]
    return "\n".join(lines)
