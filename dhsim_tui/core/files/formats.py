"""The file formats dhsim reads besides its own and writes: names and
suffixes only, so that a dialog or a parser can list them without loading
the importers and exporters (XML, CSV, JSON: ~30 ms of every start).
"""

from __future__ import annotations

#: files ``dhsim import`` (and the open dialog) turn into robots
IMPORT_SUFFIXES = (".urdf", ".csv")
#: what ``dhsim export`` writes, and each format's file suffix
EXPORT_FORMATS: tuple[str, ...] = ("urdf", "csv", "json")
EXPORT_SUFFIXES: dict[str, str] = {"urdf": ".urdf", "csv": ".csv", "json": ".json"}
