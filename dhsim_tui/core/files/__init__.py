"""Robot files: reading and writing them (TOML with comments kept), atomic
writes, crash recovery, the bundled library and the names of the other
formats.

Imports :mod:`~dhsim_tui.core.analysis` and :mod:`~dhsim_tui.core.model`.
"""
