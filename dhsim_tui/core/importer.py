"""Robots from elsewhere: ``dhsim import`` of a ``.urdf`` or ``.csv`` file.

The URDF importer is :mod:`dhsim_tui.core.urdf_import`, the CSV one
:mod:`dhsim_tui.core.csv_import`; this module reads the file and hands it on.
"""

from __future__ import annotations

import os
from pathlib import Path

from dhsim_tui.core.atomicfile import read_file
from dhsim_tui.core.csv_import import from_csv
from dhsim_tui.core.errors import DhsimError
from dhsim_tui.core.formats import IMPORT_SUFFIXES
from dhsim_tui.core.imported import ImportResult
from dhsim_tui.core.text import printable
from dhsim_tui.core.urdf_import import from_urdf

#: files larger than this are refused before parsing (a URDF with meshes listed is < 1 MB)
MAX_IMPORT_BYTES = 20_000_000

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
    raw, _ = read_file(path, MAX_IMPORT_BYTES)
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
