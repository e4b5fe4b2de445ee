"""A URDF's link tree (:mod:`dhsim_tui.core.interop.urdf`): its links and
joints by name, checked to form one tree (one parent per link, no cycle, one
root), and the only leaf below a link, or :class:`TipNeeded` naming the
leaves to choose from.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass

from dhsim_tui.core.interop.imported import quoted
from dhsim_tui.core.model.errors import DhsimError, TipNeeded


def link_names(robot: ET.Element) -> list[str]:
    """Every ``<link>``'s name, in file order; each must be named and unique."""
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


def joint_edges(robot: ET.Element, links: list[str]) -> list[_Edge]:
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


def check_tree(links: list[str], joints: list[_Edge], parent_joint: dict[str, _Edge]) -> None:
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


def only_leaf(base: str, links: list[str], joints: list[_Edge]) -> str:
    """The one leaf link below ``base`` (the chain's tip); :class:`TipNeeded`,
    listing them, if there are several."""
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


def links_hint(links: list[str]) -> str:
    """`` (links: ...)``: the link names, for an error message."""
    return f" (links: {_listed(links)})"


def _listed(names: list[str], separator: str = ", ", most: int = 10) -> str:
    """The first ``most`` names, each quoted and cut to 60 characters, and how
    many more there are."""
    shown = separator.join(quoted(name, 60) for name in names[:most])
    more = len(names) - most
    return shown + (f"{separator}... ({more} more)" if more > 0 else "")
