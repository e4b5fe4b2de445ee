"""What changed between two robots, in words: for undo and redo messages
("undid: joint 2 alpha 90 -> 0"). Names from the file are escaped."""

from __future__ import annotations

from dhsim_tui.core.model.editing import JOINT_FIELDS
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.tui.screens.editor_table import number, numbers

#: how many changes a message lists before "and N more"
SHOWN = 2
#: old and new values longer than this together are not quoted (the status
#: line has two lines at 80 columns; the table shows the new value)
QUOTED = 60


def describe_change(before: Robot, after: Robot) -> str:
    """The change from ``before`` to ``after`` (the first few, if several)."""
    changes = _changes(before, after)
    if not changes:
        return "nothing changed"
    text = "; ".join(changes[:SHOWN])
    if len(changes) > SHOWN:
        text += f"; and {len(changes) - SHOWN} more"
    return text


def _changes(before: Robot, after: Robot) -> list[str]:
    if before.units != after.units:  # every length was converted: that is the change
        return [f"units {before.units} -> {after.units}"]
    joints = _joint_changes(before, after)
    changes = list(joints)
    for name, old, new in (
        ("name", printable(before.name), printable(after.name)),
        ("convention", before.convention, after.convention),
        ("base height", number(before.base_height), number(after.base_height)),
        ("base z", before.base_z, after.base_z),
        ("base x", before.base_x, after.base_x),
        ("base xyz", numbers(before.base_xyz), numbers(after.base_xyz)),
        ("base rpy", numbers(before.base_rpy), numbers(after.base_rpy)),
        ("tool xyz", numbers(before.tool.xyz), numbers(after.tool.xyz)),
        ("tool rpy", numbers(before.tool.rpy), numbers(after.tool.rpy)),
    ):
        if old != new:
            changes.append(_quoted(name, old, new))
    if not joints:  # a joint edit moves pose values with it: not news
        changes += _pose_changes(before, after)
    return changes


def _joint_changes(before: Robot, after: Robot) -> list[str]:
    old, new = before.joints, after.joints
    if len(old) != len(new):
        first = next(
            (i for i, (a, b) in enumerate(zip(old, new, strict=False)) if a != b),
            min(len(old), len(new)),
        )
        if len(new) > len(old):
            return [f"joint {first + 1} added"]
        return [f"joint {first + 1} deleted"]
    differ = [i for i, (a, b) in enumerate(zip(old, new, strict=True)) if a != b]
    if len(differ) == 2 and (old[differ[0]], old[differ[1]]) == (new[differ[1]], new[differ[0]]):
        return [f"joint {differ[0] + 1} swapped with joint {differ[1] + 1}"]
    changes = []
    for i in differ:
        a, b = old[i], new[i]
        if a.type != b.type:
            changes.append(f"joint {i + 1} {a.type} -> {b.type}")
            continue
        for field in JOINT_FIELDS:
            va, vb = getattr(a, field), getattr(b, field)
            if va != vb:
                changes.append(f"joint {i + 1} {field} {number(va)} -> {number(vb)}")
    return changes


def _pose_changes(before: Robot, after: Robot) -> list[str]:
    old, new = dict(before.poses), dict(after.poses)
    changes = []
    for name in old.keys() - new.keys():
        changes.append(f"pose {printable(name)} deleted")
    for name in new.keys() - old.keys():
        changes.append(f"pose {printable(name)} added")
    for name in old.keys() & new.keys():
        if old[name] != new[name]:
            what = f"pose {printable(name)}"
            changes.append(_quoted(what, numbers(old[name]), numbers(new[name])))
    return sorted(changes)


def _quoted(what: str, old: str, new: str) -> str:
    if len(old) + len(new) > QUOTED:
        return f"{what} changed"
    return f"{what} {old} -> {new}"
