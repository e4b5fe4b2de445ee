"""dhsim: a terminal simulator for serial robot arms built from D-H parameters.

Importing the package loads nothing but the standard library: the core lives
in :mod:`dhsim_tui.core` (numpy only) and the terminal UI in
:mod:`dhsim_tui.tui.app`, which is imported only when the simulator opens.
"""

__version__ = "0.1.0"
