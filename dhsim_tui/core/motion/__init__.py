"""Moving the arm: joint and Cartesian jogging, smooth motion between poses
and cycling through the IK branches of a pose.

The top layer of the core: imports :mod:`~dhsim_tui.core.ik`,
:mod:`~dhsim_tui.core.analysis` and :mod:`~dhsim_tui.core.model`.
"""
