"""The terminal UI (Textual): the app, its screens, flows and widgets.

It arranges, binds keys and renders; the numbers come from
:mod:`dhsim_tui.core` and the drawings from :mod:`dhsim_tui.scene` and
:mod:`dhsim_tui.render`.
"""
