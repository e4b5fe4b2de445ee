"""Where dhsim's words go: results on stdout; errors, remarks and a report
that stdout cannot carry on stderr (:func:`to_stderr`), and never the one
for the other.

Standard error may be unusable: closed (``2>&-``: Python then has no
``sys.stderr``, and ``print(file=sys.stderr)`` would quietly write to
stdout, into a CSV or a robot file) or full (``2>/dev/full``). A line that
cannot be written is dropped: the command keeps its exit status (2 for a
usage error, 3 when ``dhsim run`` found problems, 0 when a remark was lost)
and its stdout stays what the command meant it to be.
"""

from __future__ import annotations

import contextlib
import os
import sys


def to_stderr(text: str) -> None:
    """``text`` and a newline on stderr; nothing when stderr is closed or
    cannot be written (never on stdout)."""
    stream = sys.stderr
    if stream is None:  # descriptor 2 closed when Python started
        return
    try:
        stream.write(f"{text}\n")
        stream.flush()
    except (OSError, ValueError):
        silence(stream)


def silence(stream) -> None:
    """Point ``stream``'s descriptor at /dev/null: what is still buffered for
    it (a write that failed) goes nowhere when Python flushes it at exit,
    where a failure would turn the exit status into 120."""
    with contextlib.suppress(AttributeError, ValueError, OSError):
        devnull = os.open(os.devnull, os.O_WRONLY)
        try:
            os.dup2(devnull, stream.fileno())
        finally:
            os.close(devnull)


def hold_closed_stderr() -> None:
    """With descriptor 2 closed (``2>&-``), the next file dhsim opens (a
    robot being saved) would get its number, and whatever writes to
    descriptor 2 would write into it: hold the number on /dev/null, and
    make ``sys.stderr`` a stream to it, so that a ``print(file=sys.stderr)``
    anywhere (the simulator's last words) goes nowhere, not to stdout."""
    if sys.stderr is not None:
        return
    try:
        os.fstat(2)
        return  # open after all
    except OSError:
        pass
    with contextlib.suppress(OSError):
        devnull = os.open(os.devnull, os.O_WRONLY)
        if devnull != 2:
            os.dup2(devnull, 2)
            os.close(devnull)
        sys.stderr = open(2, "w", encoding="utf-8", errors="replace", closefd=False)  # noqa: SIM115
