"""What a pose or an arm can do: the Jacobian and its conditioning, reach
and the workspace.

Imports :mod:`dhsim_tui.core.model` only.
"""
