"""Exporting a robot from the UI: a format, a file name, a question before
replacing a file, and a line saying where it went.

Used by the editor's ``x`` and the command palette (editor and simulator).
The text is the core's (:mod:`dhsim_tui.core.interop.export`); this module only
asks. Call :func:`export_flow` from a ``@work`` worker (it asks questions
with ``push_screen_wait``).
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable
from pathlib import Path

from textual.app import App

from dhsim_tui.core.files.formats import EXPORT_FORMATS, EXPORT_SUFFIXES
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.terminal.charset import shown
from dhsim_tui.tui.flows.save import MESSAGE_PATH_LIMIT, suggested_name
from dhsim_tui.tui.screens.dialogs import Choice, Confirm, reason_of, short_path
from dhsim_tui.tui.screens.open_robot import ROBOTS_DIR
from dhsim_tui.tui.screens.value_entry import ValueEntry

#: how a flow tells the user something: (message, is_error)
Report = Callable[[str, bool], None]

#: what each format is for, as the format question lists it
FORMAT_TEXT = {
    "urdf": "URDF  .urdf  links and joints, for ROS tools",
    "csv": "CSV   .csv   the D-H table (dhsim opens it back)",
    "json": "JSON  .json  the whole robot as data",
}


def export_path(text: str, fmt: str) -> Path:
    """The file a typed name means for ``fmt``: the format's suffix is added
    when the name has none; another export or robot suffix is refused (a
    ``.csv`` holding URDF would not open back)."""
    stripped = text.strip()
    if not stripped:
        raise DhsimError("file: type a file name")
    path = Path(stripped)
    with contextlib.suppress(RuntimeError):  # "~someone" with no such user: as typed
        path = path.expanduser()
    suffix = EXPORT_SUFFIXES[fmt]
    known = {".toml", *EXPORT_SUFFIXES.values()}
    if path.suffix.lower() != suffix:
        if path.suffix.lower() in known:
            raise DhsimError(
                printable(f"file: a {fmt.upper()} file's name ends in {suffix}, not {path.suffix}")
            )
        if path.name in ("", ".", ".."):
            raise DhsimError(printable(f"file: {stripped!r} is a folder; give a file name"))
        path = path.with_name(path.name + suffix)
    return path


def _exists(path: Path) -> bool:
    try:
        return path.exists()
    except (OSError, ValueError):
        return False  # writing will say why


async def export_flow(
    app: App,
    robot: Robot,
    path: Path | None = None,
    *,
    report: Report | None = None,
) -> Path | None:
    """Ask a format and a file name, then write ``robot`` there; the file
    written, or None when cancelled or failed (after telling the user).
    ``path``: the robot's own file, whose name the suggested one follows."""

    def tell(message: str, error: bool = False) -> None:
        if report is not None:
            report(message, error)
        else:
            app.notify(
                shown(printable(message), app),
                severity="error" if error else "information",
                timeout=8,
                markup=False,
            )

    fmt = await app.push_screen_wait(
        Choice(
            "Export as",
            [(name, FORMAT_TEXT[name]) for name in EXPORT_FORMATS],
            "urdf",
            hint="↑↓ choose · enter picks · escape cancels",
        )
    )
    if fmt is None:
        tell("not exported")
        return None
    suffix = EXPORT_SUFFIXES[fmt]
    target = await app.push_screen_wait(
        ValueEntry(
            f"export {fmt.upper()} to",
            str(ROBOTS_DIR / f"{suggested_name(robot, path)}{suffix}"),
            f"a file name or path; {suffix} is added when it has none",
            lambda text: export_path(text, fmt),
        )
    )
    if target is None:
        tell("not exported")
        return None
    where = short_path(target, MESSAGE_PATH_LIMIT)
    overwrite = _exists(target)
    if overwrite and not await app.push_screen_wait(
        Confirm(f"{short_path(target)} exists. Replace it?", "Replace a file")
    ):
        tell(f"not exported: {where} is left as it was")
        return None
    if target.parent == ROBOTS_DIR:
        try:
            ROBOTS_DIR.mkdir(exist_ok=True)
        except OSError as exc:
            tell(f"not exported: cannot make {ROBOTS_DIR}/: {reason_of(exc, ROBOTS_DIR)}", True)
            return None
    try:
        # the exporters, loaded when first used (not at every start)
        from dhsim_tui.core.interop.export import write_export

        written = write_export(robot, fmt, target, overwrite=overwrite)
    except (DhsimError, OSError, ValueError) as exc:
        tell(f"not exported: {reason_of(exc, target)} — {where}", True)
        return None
    tell(f"exported {fmt.upper()} to {short_path(written, MESSAGE_PATH_LIMIT)}")
    return written
