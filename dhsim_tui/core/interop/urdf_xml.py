"""A URDF's XML, read with care (:func:`parse_urdf`): a first streaming pass
(expat, which expands nothing) refuses a DOCTYPE or a declaration and stops
past :data:`MAX_URDF_NODES` elements and attributes, past
:data:`MAX_URDF_LINKS` links or joints and past :data:`MAX_URDF_DEPTH`
levels of nesting, before ElementTree builds the tree; it also keeps the
first comment that starts with :data:`DHSIM_COMMENT`.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from xml.parsers import expat

from dhsim_tui.core.interop.imported import shortened
from dhsim_tui.core.model.errors import DhsimError

#: elements and attributes together, counted while streaming (a real URDF of
#: 1000 links has about 60 000)
MAX_URDF_NODES = 200_000
#: elements nested deeper than this are refused (a URDF's are 5 deep)
MAX_URDF_DEPTH = 50
#: links, and joints, a URDF may hold (the chain uses at most 33 of them)
MAX_URDF_LINKS = 1_000
#: a comment starting with this word holds dhsim's own fields (urdf_export)
DHSIM_COMMENT = "dhsim-robot"


class _Refused(Exception):
    """Raised by the expat handlers to stop at a DOCTYPE or declaration."""


def parse_urdf(text: str) -> tuple[ET.Element, str | None]:
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
