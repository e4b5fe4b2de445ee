"""Flows: short conversations of dialogs (save, recover, export, a value to
enter, a session's first questions, the simulator's robot files) run as
workers that wait for each answer.
"""
