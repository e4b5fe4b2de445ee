"""The robot model: units, text clean-up, validation, orientation, forward
kinematics, the robot and its edits, the three-way merge.

The bottom layer of the core: it imports numpy and the standard library only.
"""
