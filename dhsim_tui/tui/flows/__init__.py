"""Flows: short conversations of dialogs (save, recover, export, a value to
enter) run as workers that wait for each answer.
"""
