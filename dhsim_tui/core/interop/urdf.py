"""A serial chain read from a URDF: the groundwork for ``dhsim import`` (issue 10).

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
at the first DOCTYPE, past :data:`MAX_URDF_NODES` elements and attributes,
past :data:`MAX_URDF_LINKS` links or joints and past :data:`MAX_URDF_DEPTH`
levels of nesting, before any tree is built;
walking the chain stops at its 33rd moving joint, before any number is read.

A comment that starts with :data:`DHSIM_COMMENT` (what ``dhsim export
--format urdf`` writes: the robot as dhsim holds it) is kept as the chain's
``stored`` text; other tools, and the chain itself, ignore it.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from xml.parsers import expat

import numpy as np

from dhsim_tui.core.interop.imported import quoted, shortened
from dhsim_tui.core.model.errors import DhsimError, TipNeeded
from dhsim_tui.core.model.text import printable
from dhsim_tui.core.model.units import MAX_ABS, MAX_JOINTS, MIN_JOINTS

#: a URDF longer than this (characters, or bytes of its file) is refused unread:
#: real ones, meshes listed by name, are well under 1 MB
MAX_URDF_BYTES = 4_000_000
#: elements and attributes together, counted while streaming (a real URDF of
#: 1000 links has about 60 000)
MAX_URDF_NODES = 200_000
#: elements nested deeper than this are refused (a URDF's are 5 deep)
MAX_URDF_DEPTH = 50
#: links, and joints, a URDF may hold (the chain uses at most 33 of them)
MAX_URDF_LINKS = 1_000
#: a comment starting with this word holds dhsim's own fields (urdf_export)
DHSIM_COMMENT = "dhsim-robot"
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


class _Refused(Exception):
    """Raised by the expat handlers to stop at a DOCTYPE or declaration."""


def _matrix(values: np.ndarray) -> np.ndarray:
    array = np.array(values, dtype=float)
    array.setflags(write=False)
    return array


@dataclass(frozen=True, eq=False)
class UrdfJoint:
    """One joint on the chain, as the URDF gives it.

    ``origin`` (4×4) places the joint frame in the parent link's frame;
    ``axis`` is a unit vector in the joint frame. ``kind`` is ``"revolute"``
    (``continuous`` tells a continuous joint), ``"prismatic"`` or
    ``"fixed"``; ``lower``/``upper`` are radians or metres (0 for a fixed
    joint). The arrays are read-only.
    """

    name: str
    kind: str
    origin: np.ndarray
    axis: np.ndarray
    lower: float
    upper: float
    continuous: bool = False

    @property
    def moves(self) -> bool:
        return self.kind != "fixed"

    def motion(self, q: float) -> np.ndarray:
        """The joint's motion (4×4) in its own frame at value ``q``."""
        m = np.eye(4)
        if self.kind == "revolute":
            m[:3, :3] = _rotation(self.axis, q)
        elif self.kind == "prismatic":
            m[:3, 3] = q * self.axis
        return m

    def transform(self, q: float) -> np.ndarray:
        """Child link in parent link: ``origin @ motion(q)``."""
        return self.origin @ self.motion(q)


@dataclass(frozen=True, eq=False)
class UrdfChain:
    """The joints from link ``base`` to link ``tip``, in order, fixed ones included."""

    base: str
    tip: str
    joints: tuple[UrdfJoint, ...]
    name: str = ""  # the <robot name="..."> attribute
    #: the text of the file's first :data:`DHSIM_COMMENT` comment, or None
    stored: str | None = None

    @property
    def moving(self) -> tuple[UrdfJoint, ...]:
        """The joints that move (revolute, continuous, prismatic), in order."""
        return tuple(j for j in self.joints if j.moves)

    def _values(self, q: object) -> np.ndarray:
        values = np.asarray(q, dtype=float).reshape(-1)
        if not np.all(np.isfinite(values)):
            raise DhsimError("joint values must be finite numbers")
        count = len(self.moving)
        if values.shape != (count,):
            raise DhsimError(
                f"expected {count} joint values, one per moving joint, got {values.size}"
            )
        return values

    def fk(self, q: object) -> np.ndarray:
        """The tip link's pose (4×4) in the base link's frame; ``q`` holds one
        value per moving joint, radians or metres. Limits are not checked."""
        values = iter(self._values(q))
        pose = np.eye(4)
        for joint in self.joints:
            pose = pose @ joint.transform(next(values) if joint.moves else 0.0)
        return pose

    def tip_home(self) -> np.ndarray:
        """The tip's pose with every joint at zero."""
        return self.fk(np.zeros(len(self.moving)))

    def joint_lines(self) -> list[tuple[str, np.ndarray, np.ndarray]]:
        """For each moving joint, ``(kind, point, direction)`` of its axis line
        in the base frame with every joint at zero: the point is the joint
        frame's origin, the direction a unit vector."""
        lines = []
        pose = np.eye(4)
        for joint in self.joints:
            frame = pose @ joint.origin
            if joint.moves:
                lines.append((joint.kind, frame[:3, 3].copy(), frame[:3, :3] @ joint.axis))
            pose = frame  # the motion is the identity at zero
        return lines


def _rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rotation by ``angle`` about the unit vector ``axis`` (Rodrigues)."""
    x, y, z = axis
    c, s = math.cos(angle), math.sin(angle)
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return c * np.eye(3) + s * k + (1 - c) * np.outer(axis, axis)


def rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """``Rz(yaw) @ Ry(pitch) @ Rx(roll)``: the URDF's fixed-axis roll, pitch, yaw."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


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
    robot, stored = _parse(text)
    links = _links(robot)
    joints = _joints(robot, links)
    parent_joint = {j.child: j for j in joints}
    _check_tree(links, joints, parent_joint)
    known = set(links)
    if base is None:
        base = next(link for link in links if link not in parent_joint)
    elif base not in known:
        raise DhsimError(f"base: no link named {quoted(base)}{_hint(links)}")
    if tip is None:
        tip = _only_leaf(base, links, joints)
    elif tip not in known:
        raise DhsimError(f"tip: no link named {quoted(tip)}{_hint(links)}")
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


def _parse(text: str) -> tuple[ET.Element, str | None]:
    """The ``<robot>`` element and the first :data:`DHSIM_COMMENT` comment's
    text; no DOCTYPE, no entity, well-formed, within the caps."""
    text = text.removeprefix("\ufeff")
    checker = expat.ParserCreate()
    counts = {"nodes": 0, "depth": 0, "link": 0, "joint": 0}
    comments: list[str] = []

    def refuse(*_args: object) -> None:
        raise _Refused("a DOCTYPE or declaration is not allowed in a URDF")

    def start(tag: str, attributes: list[str]) -> None:
        counts["nodes"] += 1 + len(attributes) // 2
        if counts["nodes"] > MAX_URDF_NODES:
            raise _Refused(
                f"more than {MAX_URDF_NODES} XML elements and attributes; "
                "dhsim reads URDFs of fewer"
            )
        counts["depth"] += 1
        if counts["depth"] > MAX_URDF_DEPTH:
            raise _Refused(f"elements nested more than {MAX_URDF_DEPTH} deep; a URDF's are not")
        if tag in ("link", "joint") and counts["depth"] == 2:  # the robot's own
            counts[tag] += 1
            if counts[tag] > MAX_URDF_LINKS:
                raise _Refused(
                    f"more than {MAX_URDF_LINKS} <{tag}> elements; "
                    f"dhsim reads URDFs of at most {MAX_URDF_LINKS}"
                )

    def end(_tag: str) -> None:
        counts["depth"] -= 1

    def comment(data: str) -> None:
        if not comments and data.lstrip().startswith(DHSIM_COMMENT):
            comments.append(data)

    checker.StartDoctypeDeclHandler = refuse
    checker.EntityDeclHandler = refuse
    checker.ElementDeclHandler = refuse
    checker.AttlistDeclHandler = refuse
    checker.ordered_attributes = True
    checker.StartElementHandler = start
    checker.EndElementHandler = end
    checker.CommentHandler = comment
    try:
        checker.Parse(text, True)
    except _Refused as exc:
        raise DhsimError(f"line {checker.CurrentLineNumber}: {exc}") from None
    except (expat.ExpatError, ValueError, RecursionError) as exc:  # ValueError: a lone surrogate
        raise DhsimError(f"not valid XML: {exc}") from None
    try:
        root = ET.fromstring(text)
    except (ET.ParseError, ValueError, RecursionError) as exc:
        raise DhsimError(f"not valid XML: {exc}") from None
    if root.tag != "robot":
        raise DhsimError(f"the top element is <{shortened(root.tag, 60)}>; a URDF's is <robot>")
    return root, (comments[0] if comments else None)


def _links(robot: ET.Element) -> list[str]:
    names: list[str] = []
    seen: set[str] = set()
    for element in robot.findall("link"):
        name = element.get("name")
        if not name:
            raise DhsimError("a <link> has no name")
        if name in seen:
            raise DhsimError(f"two links are named {quoted(name)}")
        seen.add(name)
        names.append(name)
    if not names:
        raise DhsimError("the robot has no <link>")
    return names


@dataclass(frozen=True)
class _Edge:
    """A ``<joint>`` as the link tree sees it."""

    name: str
    parent: str
    child: str
    element: ET.Element


def _joints(robot: ET.Element, links: list[str]) -> list[_Edge]:
    """Every ``<joint>``, each with a unique name and existing parent and child links."""
    known = set(links)
    joints = []
    seen: set[str] = set()
    for element in robot.findall("joint"):
        name = element.get("name")
        if not name:
            raise DhsimError("a <joint> has no name")
        if name in seen:
            raise DhsimError(f"two joints are named {quoted(name)}")
        seen.add(name)
        ends = []
        for end in ("parent", "child"):
            tags = element.findall(end)
            if len(tags) != 1:
                count = "no" if not tags else "more than one"
                raise DhsimError(f"joint {quoted(name)}: {count} <{end} link=...>")
            link = tags[0].get("link")
            if not link:
                raise DhsimError(f"joint {quoted(name)}: <{end}> has no link")
            if link not in known:
                raise DhsimError(
                    f"joint {quoted(name)}: {end} link {quoted(link)} is not a <link> of the robot"
                )
            ends.append(link)
        joints.append(_Edge(name, ends[0], ends[1], element))
    return joints


def _check_tree(links: list[str], joints: list[_Edge], parent_joint: dict[str, _Edge]) -> None:
    """One parent per link, no cycle, one root."""
    seen: dict[str, str] = {}
    for edge in joints:
        if edge.child in seen:
            raise DhsimError(
                f"link {quoted(edge.child)} has two parents: joints "
                f"{quoted(seen[edge.child])} and {quoted(edge.name)} both lead to it"
            )
        seen[edge.child] = edge.name
    done: set[str] = set()
    for start in links:
        trail: list[str] = []
        on_trail: set[str] = set()
        link = start
        while link in parent_joint and link not in done:
            if link in on_trail:
                loop = [*trail[trail.index(link) :], link]
                raise DhsimError("the joints form a cycle: links " + _listed(loop, " <- "))
            trail.append(link)
            on_trail.add(link)
            link = parent_joint[link].parent
        done.update(trail)
    roots = [link for link in links if link not in parent_joint]
    if len(roots) != 1:
        raise DhsimError(
            f"the links form {len(roots)} separate trees, with roots "
            + _listed(roots)
            + "; a URDF has one root link"
        )


def _only_leaf(base: str, links: list[str], joints: list[_Edge]) -> str:
    children: dict[str, list[str]] = {link: [] for link in links}
    for edge in joints:
        children[edge.parent].append(edge.child)
    leaves = []
    pending = [base]
    while pending:
        link = pending.pop()
        if children[link]:
            pending.extend(reversed(children[link]))
        else:
            leaves.append(link)
    if len(leaves) > 1:
        raise TipNeeded(
            f"the links below {quoted(base)} form a tree, not a chain; choose a tip among its "
            f"{len(leaves)} leaf links: " + _listed(leaves),
            tuple(leaves),
        )
    return leaves[0]


def _hint(links: list[str]) -> str:
    return f" (links: {_listed(links)})"


def _listed(names: list[str], separator: str = ", ", most: int = 10) -> str:
    """The first ``most`` names, each quoted and cut to 60 characters, and how
    many more there are."""
    shown = separator.join(quoted(name, 60) for name in names[:most])
    more = len(names) - most
    return shown + (f"{separator}... ({more} more)" if more > 0 else "")


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
        origin=_matrix(origin),
        axis=_matrix(axis),
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
