"""Screens: the simulator (control), the editor, the start question, help,
the palette and the dialogs. A screen composes widgets and answers their
messages by asking the core.
"""
