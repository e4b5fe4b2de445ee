"""Inverse kinematics: the numerical solver, every solution (closed forms
detected from the D-H table, seeded search elsewhere), configuration labels
and the reasons a target is not reached.

Imports :mod:`~dhsim_tui.core.analysis` and :mod:`~dhsim_tui.core.model`.
"""
