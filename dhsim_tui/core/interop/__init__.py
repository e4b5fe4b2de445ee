"""Other tools' files: URDF and CSV imports, D-H extraction, the
standard/modified conversion and the URDF, CSV and JSON exports.

Imports :mod:`~dhsim_tui.core.files`, :mod:`~dhsim_tui.core.analysis` and
:mod:`~dhsim_tui.core.model`.
"""
