"""Widgets: they arrange and render what the screens hand them, never compute kinematics."""
