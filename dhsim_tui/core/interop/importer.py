"""Robots from elsewhere: ``dhsim import`` of a ``.urdf`` or ``.csv`` file.

The URDF importer is :mod:`dhsim_tui.core.interop.urdf_import`, the CSV one
:mod:`dhsim_tui.core.interop.csv_import`; this module reads the file and hands it on.
A file larger than its kind's cap (:data:`MAX_IMPORT_BYTES`) is refused by
its size, before a byte of it is read.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from dhsim_tui.core.files.atomicfile import read_file
from dhsim_tui.core.files.formats import IMPORT_SUFFIXES
from dhsim_tui.core.interop.csv_import import MAX_CSV_BYTES, from_csv
from dhsim_tui.core.interop.imported import ImportResult
from dhsim_tui.core.interop.urdf import MAX_URDF_BYTES
from dhsim_tui.core.interop.urdf_import import from_urdf
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.text import printable

#: files larger than this are refused unread, by kind
MAX_IMPORT_BYTES = {".urdf": MAX_URDF_BYTES, ".csv": MAX_CSV_BYTES}

__all__ = ["IMPORT_SUFFIXES", "ImportResult", "from_csv", "from_urdf", "import_file"]


def import_file(
    path: str | os.PathLike[str],
    *,
    tip: str | None = None,
    base: str | None = None,
    convention: str | None = None,
    units: str | None = None,
    name: str | None = None,
) -> ImportResult:
    """Import a ``.urdf`` or ``.csv`` file; DhsimError (one line, naming the file)."""
    path = Path(path)
    kind = path.suffix.lower()
    if kind not in IMPORT_SUFFIXES:
        raise DhsimError(
            printable(
                f"{path}: dhsim imports {' and '.join(IMPORT_SUFFIXES)} files, "
                f"not {kind or 'a file without a suffix'}"
            )
        )
    limit = MAX_IMPORT_BYTES[kind]
    try:
        info = path.stat()
    except (OSError, ValueError):
        info = None  # read_file says what is wrong
    if info is not None and stat.S_ISREG(info.st_mode) and info.st_size > limit:
        raise DhsimError(
            printable(
                f"{path}: {info.st_size} bytes is more than dhsim imports from a {kind} file "
                f"({limit} at most)"
            )
        )
    raw, _ = read_file(path, limit)
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise DhsimError(
            printable(f"{path}: not a text file (invalid UTF-8 at byte {exc.start})")
        ) from None
    if kind == ".urdf":
        return from_urdf(
            text,
            source=str(path),
            tip=tip,
            base=base,
            convention=convention,
            units=units,
            name=name,
        )
    if tip is not None or base is not None:
        raise DhsimError(printable(f"{path}: --tip and --base are for URDF files"))
    return from_csv(
        text, source=str(path), convention=convention, units=units, name=name or path.stem
    )
