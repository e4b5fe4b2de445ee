"""Screens of the simulator: control (joints, pose, views), help, value entry."""
