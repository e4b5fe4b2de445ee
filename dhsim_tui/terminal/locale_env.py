"""Which character set the terminal has: read from the locale and ``TERM``.

A C locale or a Linux console (``TERM=linux``, whose fonts lack most of the
glyphs) means 7-bit ASCII (:func:`wants_ascii`; ``--ascii`` and ``--unicode``
decide instead when given). The locale must be read from the environment the
process was started with: CPython (PEP 538) sets ``LC_CTYPE=C.UTF-8`` in
``os.environ`` at start-up when the locale is C, so ``os.environ`` says UTF-8
exactly when the terminal is not. :func:`original_environ` undoes that from
``/proc/self/environ``, which the kernel keeps as it was at exec. The command
line imports this module before Textual is: it imports neither Textual nor
Rich.
"""

from __future__ import annotations

import os
from collections.abc import Mapping

#: the variables that name the character set, strongest first (POSIX)
LOCALE_VARIABLES = ("LC_ALL", "LC_CTYPE", "LANG")
#: what PEP 538 writes into LC_CTYPE when it coerces the C locale
COERCED_CTYPES = frozenset({"C.UTF-8", "C.utf8", "UTF-8"})
#: where Linux keeps the environment a process was started with
PROC_ENVIRON = "/proc/self/environ"


def _read_proc_environ(path: str) -> dict[str, str] | None:
    try:
        with open(path, "rb") as file:
            raw = file.read()
    except OSError:  # not Linux, no /proc, or not readable
        return None
    environ: dict[str, str] = {}
    for entry in raw.split(b"\0"):
        name, sep, value = entry.partition(b"=")
        if sep and name:
            environ[os.fsdecode(name)] = os.fsdecode(value)
    return environ


def original_environ(
    environ: Mapping[str, str] | None = None, proc_environ: str = PROC_ENVIRON
) -> dict[str, str]:
    """``environ`` (default: ``os.environ``) with ``LC_CTYPE`` as the process
    was started with, when Python's locale coercion (PEP 538) changed it.

    Only that change is undone: the variables as the program sees them are
    kept otherwise (a test may set them). Where ``/proc`` cannot be read
    (not Linux), ``environ`` as it is.
    """
    current = dict(os.environ if environ is None else environ)
    ctype = current.get("LC_CTYPE")
    if ctype not in COERCED_CTYPES:
        return current
    started = _read_proc_environ(proc_environ)
    if started is None or started.get("LC_CTYPE") == ctype:
        return current
    if "LC_CTYPE" in started:
        current["LC_CTYPE"] = started["LC_CTYPE"]
    else:
        del current["LC_CTYPE"]
    return current


def is_utf8_locale(name: str) -> bool:
    """``en_US.UTF-8``, ``C.utf8``, ``UTF-8``... (any case); not ``C``,
    ``POSIX``, ``en_US`` (Latin-1) or ``de_DE.ISO-8859-15``."""
    lowered = name.lower()
    return "utf-8" in lowered or "utf8" in lowered


def wants_ascii(environ: Mapping[str, str], *, force: bool | None = None) -> bool:
    """True when the screen must be 7-bit ASCII.

    ``force`` (``--ascii`` True, ``--unicode`` False) decides if given.
    Otherwise: ``TERM=linux`` (the Linux console) is ASCII; else the first
    non-empty of LC_ALL, LC_CTYPE, LANG decides: UTF-8 or not. None of them
    set is the C locale: ASCII.
    """
    if force is not None:
        return force
    if environ.get("TERM", "") == "linux":
        return True
    for variable in LOCALE_VARIABLES:
        value = environ.get(variable, "")
        if value:
            return not is_utf8_locale(value)
    return True
