"""Widgets: each owns its keys, mouse handling and state and posts messages;
none computes kinematics.
"""
