"""A serial chain read from a URDF: what ``dhsim import`` turns into a D-H table.

:func:`read_chain` walks the link tree of a URDF from its root (or ``base``)
to ``tip`` and keeps the joints on that path, in order: fixed, revolute,
continuous and prismatic joints, with axes in any direction. What it returns
is the URDF's own kinematics (a fixed transform and a motion per joint), not
D-H parameters; turning the chain into a D-H table is a later step.

Conventions are the URDF specification's:

* a joint's ``<origin xyz rpy>`` is the joint frame in its parent link's
  frame; both default to zero; ``rpy`` is roll, pitch, yaw about the fixed
  axes x, y, z, so the rotation is ``Rz(yaw) @ Ry(pitch) @ Rx(roll)``;
* ``<axis xyz>`` is in the joint frame, defaults to ``1 0 0`` and is
  normalised here (a zero axis is refused);
* the child link's frame is the joint frame moved by the joint: a rotation
  about the axis (radians) or a translation along it (metres);
* revolute and prismatic joints need ``<limit lower upper>``, which are kept;
  continuous joints get a full turn each way, ``-2π..2π``, whatever their
  ``<limit>`` says.

Everything a user can get wrong raises :class:`DhsimError` with one line that
starts with ``source`` (when given) and names the culprit, with file text
escaped by :func:`printable` and cut in the middle past 200 characters:
malformed XML, a DOCTYPE or entity declaration (refused before anything is
expanded), a missing or duplicate link, a link with two parents, a cycle,
more than one root, a non-finite number, a zero axis, missing limits; on the
chain, a mimic, floating or planar joint, or more moving joints than a robot
holds. Joints off the chain are checked only for what the tree needs (their
name, parent and child); their numbers are not read.

A hostile file costs little: the text is at most :data:`MAX_URDF_BYTES`
characters, and a first streaming pass (expat, which expands nothing) stops
at the first DOCTYPE, past
:data:`~dhsim_tui.core.interop.urdf_xml.MAX_URDF_NODES` elements and
attributes, past :data:`~dhsim_tui.core.interop.urdf_xml.MAX_URDF_LINKS`
links or joints and past :data:`~dhsim_tui.core.interop.urdf_xml.MAX_URDF_DEPTH`
levels of nesting, before any tree is built (:mod:`dhsim_tui.core.interop.urdf_xml`);
walking the chain stops at its 33rd moving joint, before any number is read.

A comment that starts with :data:`~dhsim_tui.core.interop.urdf_xml.DHSIM_COMMENT`
(what ``dhsim export --format urdf`` writes: the robot as dhsim holds it) is
kept as the chain's ``stored`` text; other tools, and the chain itself,
ignore it.

The chain it returns is :mod:`dhsim_tui.core.interop.urdf_chain`'s, the link
tree's checks :mod:`dhsim_tui.core.interop.urdf_tree`'s.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET

import numpy as np

from dhsim_tui.core.interop.imported import quoted
from dhsim_tui.core.interop.urdf_chain import UrdfChain, UrdfJoint, frozen_matrix, rpy_matrix
from dhsim_tui.core.interop.urdf_tree import (
    check_tree,
    joint_edges,
    link_names,
    links_hint,
    only_leaf,
)
from dhsim_tui.core.interop.urdf_xml import parse_urdf
from dhsim_tui.core.model.errors import DhsimError, TipNeeded
from dhsim_tui.core.model.text import printable
from dhsim_tui.core.model.units import MAX_ABS, MAX_JOINTS, MIN_JOINTS

#: a URDF longer than this (characters, or bytes of its file) is refused unread:
#: real ones, meshes listed by name, are well under 1 MB
MAX_URDF_BYTES = 4_000_000
#: the range given to a continuous joint: a full turn each way (radians)
CONTINUOUS_LIMIT = 2 * math.pi
#: URDF joint types the chain may hold, and the kind each becomes
_KINDS = {
    "revolute": "revolute",
    "continuous": "revolute",
    "prismatic": "prismatic",
    "fixed": "fixed",
}
#: URDF joint types that are refused on the chain
_REFUSED_TYPES = ("floating", "planar")
#: a decimal number as the URDF tools write one (no nan, inf, hex or underscores)
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")


# -- reading ----------------------------------------------------------------------


def read_chain(
    text: str, *, tip: str | None = None, base: str | None = None, source: str = ""
) -> UrdfChain:
    """The serial chain of the URDF ``text`` from ``base`` (default: the root
    link) to ``tip`` (default: the only leaf below ``base``).

    Raises :class:`DhsimError`, one line starting with ``source`` (when
    given), for anything wrong with the file or the names given.
    """
    prefix = f"{source}: " if source else ""
    try:
        if len(text) > MAX_URDF_BYTES:
            raise DhsimError(
                f"{len(text)} characters is more than dhsim reads from a URDF "
                f"({MAX_URDF_BYTES} at most)"
            )
        return _read_chain(text, tip, base)
    except TipNeeded as exc:
        raise TipNeeded(printable(f"{prefix}{exc}"), exc.leaves) from None
    except DhsimError as exc:
        raise DhsimError(printable(f"{prefix}{exc}")) from None


def _read_chain(text: str, tip: str | None, base: str | None) -> UrdfChain:
    robot, stored = parse_urdf(text)
    links = link_names(robot)
    joints = joint_edges(robot, links)
    parent_joint = {j.child: j for j in joints}
    check_tree(links, joints, parent_joint)
    known = set(links)
    if base is None:
        base = next(link for link in links if link not in parent_joint)
    elif base not in known:
        raise DhsimError(f"base: no link named {quoted(base)}{links_hint(links)}")
    if tip is None:
        tip = only_leaf(base, links, joints)
    elif tip not in known:
        raise DhsimError(f"tip: no link named {quoted(tip)}{links_hint(links)}")
    path = []
    moving = 0
    link = tip
    while link != base:
        if link not in parent_joint:
            raise DhsimError(
                f"link {quoted(base)} is not an ancestor of link {quoted(tip)}; no chain joins them"
            )
        edge = parent_joint[link]
        moving += edge.element.get("type") != "fixed"
        if moving > MAX_JOINTS:
            raise DhsimError(
                f"the chain from link {quoted(base)} to link {quoted(tip)} has more than "
                f"{MAX_JOINTS} moving joints; a robot has {MIN_JOINTS} to {MAX_JOINTS}"
            )
        path.append(edge)
        link = edge.parent
    chain = tuple(_joint(edge.name, edge.element) for edge in reversed(path))
    if not any(j.moves for j in chain):
        raise DhsimError(f"no moving joint between link {quoted(base)} and link {quoted(tip)}")
    return UrdfChain(
        base=base, tip=tip, joints=chain, name=robot.get("name", "") or "", stored=stored
    )


def _joint(name: str, element: ET.Element) -> UrdfJoint:
    where = f"joint {quoted(name)}"
    urdf_type = element.get("type")
    if urdf_type in _REFUSED_TYPES:
        raise DhsimError(f"{where}: a {urdf_type} joint cannot be part of an arm")
    if urdf_type not in _KINDS:
        listed = ", ".join(_KINDS)
        shown = "no type" if urdf_type is None else f"type {quoted(urdf_type, 60)}"
        raise DhsimError(f"{where}: {shown}; the chain's joints are {listed}")
    if element.find("mimic") is not None:
        raise DhsimError(f"{where}: a mimic joint (moved by another joint) cannot be imported")
    kind = _KINDS[urdf_type]
    origin_tag = element.find("origin")
    xyz = _triple(origin_tag, "xyz", (0.0, 0.0, 0.0), f"{where}: <origin xyz>")
    rpy = _triple(origin_tag, "rpy", (0.0, 0.0, 0.0), f"{where}: <origin rpy>")
    origin = np.eye(4)
    origin[:3, :3] = rpy_matrix(*rpy)
    origin[:3, 3] = xyz
    axis = np.array(_triple(element.find("axis"), "xyz", (1.0, 0.0, 0.0), f"{where}: <axis xyz>"))
    if kind != "fixed":
        norm = float(np.linalg.norm(axis))
        if norm == 0:
            raise DhsimError(f"{where}: <axis xyz> is zero; a joint needs a direction")
        axis = axis / norm
    lower = upper = 0.0
    if urdf_type == "continuous":
        lower, upper = -CONTINUOUS_LIMIT, CONTINUOUS_LIMIT
    elif kind != "fixed":
        limit = element.find("limit")
        if limit is None:
            raise DhsimError(f"{where}: a {urdf_type} joint needs <limit lower=... upper=...>")
        lower = _number(limit, "lower", f"{where}: <limit lower>")
        upper = _number(limit, "upper", f"{where}: <limit upper>")
        if not lower < upper:
            raise DhsimError(
                f"{where}: <limit> lower ({lower:g}) must be less than upper ({upper:g})"
            )
    return UrdfJoint(
        name=name,
        kind=kind,
        origin=frozen_matrix(origin),
        axis=frozen_matrix(axis),
        lower=lower,
        upper=upper,
        continuous=urdf_type == "continuous",
    )


def _triple(
    tag: ET.Element | None, key: str, default: tuple[float, float, float], where: str
) -> tuple[float, float, float]:
    if tag is None or tag.get(key) is None:
        return default
    words = tag.get(key, "").split()
    if len(words) != 3:
        raise DhsimError(f"{where}: expected 3 numbers, got {len(words)}")
    x, y, z = (_finite(word, where) for word in words)
    return (x, y, z)


def _number(tag: ET.Element, key: str, where: str) -> float:
    word = tag.get(key)
    if word is None:
        raise DhsimError(f"{where}: missing")
    return _finite(word.strip(), where)


def _finite(word: str, where: str) -> float:
    if not _NUMBER.fullmatch(word):
        raise DhsimError(f"{where}: {quoted(word, 60)} is not a finite number")
    value = float(word)
    if not math.isfinite(value) or abs(value) > MAX_ABS:
        raise DhsimError(f"{where}: {quoted(word, 60)} is out of range (|value| <= {MAX_ABS:g})")
    return value
