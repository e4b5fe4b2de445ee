"""The command line: a thin shell over the core, one module per group of
commands. ``dhsim_tui.cli.main:main`` is the ``dhsim`` entry point.
"""
