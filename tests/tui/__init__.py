"""A package, so its conftest is ``tui.conftest``: the tests here and in the
other folders that say ``from conftest import ...`` get tests/conftest.py."""
