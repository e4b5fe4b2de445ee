"""A robot as a URDF (``dhsim export --format urdf``).

A serial chain for rviz and friends. The robot is first converted to the
modified convention (:func:`~dhsim_tui.core.interop.convert.convert`), so URDF link
``link{i}`` is modified D-H frame i, which sits on joint i's axis:

- link ``world`` is dhsim's world frame (the floor is at z = -base_height);
  fixed joint ``base_joint`` places ``link0`` (frame 0) in it;
- joint ``joint{i}`` (revolute or prismatic, axis ``0 0 1``) goes from
  ``link{i-1}`` to ``link{i}``; its origin is Rx(alpha_{i-1})·Tx(a_{i-1})·
  Tz(d_i)·Rz(offset_i) (revolute) or Rx(alpha_{i-1})·Tx(a_{i-1})·
  Rz(theta_i)·Tz(offset_i) (prismatic), so the URDF joint value is dhsim's
  joint value q, in radians or metres;
- fixed joint ``tool_joint`` places link ``tool`` on ``link{n}`` (identity
  when the robot has no tool).

Limits are dhsim's min/max; effort and velocity, which URDF requires and
dhsim does not know, are placeholders (an XML comment says so). Each link
gets a cylinder from its origin to the next frame's origin and each
prismatic joint a thinner "rail" over its range, so the arm can be seen.

dhsim's own fields, which a URDF has no place for (the name as written, the
unit, the convention, the D-H table as the user wrote it, the base height
and shorthand, the named poses, limits in degrees), ride along in a second
comment before ``<robot>``, which every URDF tool ignores::

    <!-- dhsim-robot 1: ...
         {"format": "dhsim-robot", "version": 1, "name": "Puma 560", ...} -->

Its JSON object is exactly what ``dhsim export --format json`` writes for the
robot (:func:`dhsim_fields`), on one line, with any ``--`` in a string written
``-\\u002d`` (a comment may not hold two dashes) and U+FFFE/U+FFFF as
``\\ufffe``/``\\uffff``. ``dhsim import`` gives the very robot back from it
when the URDF's joints still match it (:mod:`dhsim_tui.core.interop.urdf_restore`).
"""

from __future__ import annotations

import html
import json
import math

import numpy as np

from dhsim_tui.core.analysis.workspace import reach
from dhsim_tui.core.files.programschema import programs_to_data
from dhsim_tui.core.interop.convert import convert
from dhsim_tui.core.interop.urdf_xml import DHSIM_COMMENT
from dhsim_tui.core.model.kinematics import robot_base
from dhsim_tui.core.model.orientation import cos_sin, rpy_angles
from dhsim_tui.core.model.robot import Joint, Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.core.model.units import UNITS

#: URDF requires effort (N or N·m) and velocity (m/s or rad/s) limits; dhsim has none
PLACEHOLDER_EFFORT = 100.0
PLACEHOLDER_VELOCITY = 1.0
#: link cylinders: this fraction of the arm's reach, at least MIN_RADIUS_M
RADIUS_FRACTION = 0.015
MIN_RADIUS_M = 0.001
#: a prismatic joint's rail is this much thinner than a link
RAIL_FRACTION = 0.6
#: a segment shorter than this (metres) gets no cylinder: it is rounding noise
#: (a nonzero length is at least a nanometre)
ZERO_LENGTH_M = 1e-10
#: numbers below this (radians, or of the arm's size in metres) are rounding noise
NOISE = 1e-15
#: the stored robot's format: the JSON export's (dhsim_tui.core.interop.export)
STORED_FORMAT = "dhsim-robot"
STORED_VERSION = 1
#: the JSON export's joint fields, in its order
STORED_JOINT_FIELDS = ("theta", "d", "a", "alpha", "offset", "min", "max")
#: a joint's fields stored only when set (top speed and acceleration)
STORED_OPTIONAL_JOINT_FIELDS = ("vmax", "amax")
STORED_JOINT_VALUE = "theta = q + offset (revolute), d = q + offset (prismatic)"
LINK_RGBA = "0.55 0.6 0.7 1"
RAIL_RGBA = "0.85 0.55 0.2 1"


def _rot_x(deg: float) -> np.ndarray:
    c, s = cos_sin(deg)
    m = np.eye(4)
    m[1:3, 1:3] = ((c, -s), (s, c))
    return m


def _rot_z(deg: float) -> np.ndarray:
    c, s = cos_sin(deg)
    m = np.eye(4)
    m[0:2, 0:2] = ((c, -s), (s, c))
    return m


def _move(x: float = 0.0, y: float = 0.0, z: float = 0.0) -> np.ndarray:
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


def _rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Rz(yaw)·Ry(pitch)·Rx(roll), degrees, exact at quarter turns."""
    cp, sp = cos_sin(pitch)
    ry = np.eye(4)
    ry[0, 0], ry[0, 2], ry[2, 0], ry[2, 2] = cp, sp, -sp, cp
    return _rot_z(yaw) @ ry @ _rot_x(roll)


def _num(value: float, noise: float = NOISE) -> str:
    """The shortest text that reads back as the same float; noise is 0."""
    value = float(value)
    if abs(value) < noise:
        value = 0.0
    return repr(value + 0.0)


def _triple(values, noise: float = NOISE) -> str:
    return " ".join(_num(v, noise) for v in values)


class _Urdf:
    """The URDF text of one robot (a class only to share the scale and sizes)."""

    def __init__(self, robot: Robot) -> None:
        self.source = robot
        self.robot = convert(robot, "modified")
        self.units = robot.units
        self.size = max(self.metres(reach(robot)), 1e-9)
        self.noise = NOISE * max(self.size, 1.0)
        self.radius = max(RADIUS_FRACTION * self.size, MIN_RADIUS_M)

    def metres(self, value):
        """Robot units to metres (a number or an array); mm is divided by 1000,
        so 412 mm is 0.412 m, not 0.41200000000000003."""
        if self.units == "m":
            return value
        return value * UNITS[self.units] / 1000.0

    def origin(self, matrix: np.ndarray) -> str:
        """``<origin>`` of a transform whose translation is in robot units."""
        xyz = _triple(self.metres(matrix[:3, 3]), self.noise)
        rpy = _triple(rpy_angles(matrix[:3, :3]))
        return f'<origin xyz="{xyz}" rpy="{rpy}"/>'

    def joint_origin(self, joint: Joint) -> np.ndarray:
        """Frame i in frame i-1 at joint value 0 (modified D-H)."""
        start = _rot_x(joint.alpha) @ _move(x=joint.a)
        if joint.is_revolute:  # Rz(q + offset)·Tz(d) = Tz(d)·Rz(offset)·Rz(q)
            return start @ _move(z=joint.d) @ _rot_z(joint.offset)
        return start @ _rot_z(joint.theta) @ _move(z=joint.offset)  # d = q + offset

    def cylinder(self, start: np.ndarray, end: np.ndarray, radius: float, material: str) -> str:
        """A ``<visual>`` cylinder from ``start`` to ``end`` (metres), or ''."""
        span = end - start
        length = float(np.linalg.norm(span))
        if length < ZERO_LENGTH_M:
            return ""
        middle = (start + end) / 2.0
        pitch = math.atan2(math.hypot(span[0], span[1]), span[2])
        yaw = math.atan2(span[1], span[0]) if math.hypot(span[0], span[1]) else 0.0
        return (
            "    <visual>\n"
            f'      <origin xyz="{_triple(middle, self.noise)}" '
            f'rpy="{_triple((0.0, pitch, yaw))}"/>\n'
            f'      <geometry><cylinder radius="{_num(radius)}" length="{_num(length)}"/>'
            "</geometry>\n"
            f'      <material name="{material}"/>\n'
            "    </visual>\n"
        )

    def link(self, name: str, visuals: list[str]) -> str:
        body = "".join(visuals)
        if not body:
            return f'  <link name="{name}"/>\n'
        return f'  <link name="{name}">\n{body}  </link>\n'

    def text(self) -> str:
        robot = self.robot
        n = robot.dof
        origins = [self.joint_origin(j) for j in robot.joints]
        tool = _move(*robot.tool.xyz) @ _rpy_matrix(*robot.tool.rpy)
        # what each link i sees of the next frame (joint i+1's origin, or the tool)
        nexts = [*origins, tool]
        visuals: list[list[str]] = [[] for _ in range(n + 1)]
        for i in range(n + 1):
            end = self.metres(nexts[i][:3, 3])
            visuals[i].append(self.cylinder(np.zeros(3), end, self.radius, "dhsim_link"))
        for i, joint in enumerate(robot.joints):
            if not joint.is_revolute:  # the rail the joint slides on, in link i-1
                axis = origins[i][:3, 2]
                base = self.metres(origins[i][:3, 3])
                ends = [base + axis * self.metres(v) for v in (joint.min, joint.max)]
                rail = self.cylinder(*ends, RAIL_FRACTION * self.radius, "dhsim_rail")
                visuals[i].append(rail)

        parts = [self.header(), stored_comment(self.source)]
        # html.escape, not xml.sax.saxutils: that one loads urllib (~11 ms at start-up)
        name = html.escape(_xml_safe(self.source.name), quote=True)
        parts.append(f'<robot name="{name}">\n')
        parts.append(f'  <material name="dhsim_link"><color rgba="{LINK_RGBA}"/></material>\n')
        parts.append(f'  <material name="dhsim_rail"><color rgba="{RAIL_RGBA}"/></material>\n')
        parts.append(self.link("world", []))
        for i in range(n + 1):
            parts.append(self.link(f"link{i}", visuals[i]))
        parts.append(self.link("tool", []))
        parts.append(self.fixed("base_joint", "world", "link0", robot_base(robot)))
        for i, (joint, origin) in enumerate(zip(robot.joints, origins, strict=True), start=1):
            parts.append(self.moving(i, joint, origin))
        parts.append(self.fixed("tool_joint", f"link{n}", "tool", tool))
        parts.append("</robot>\n")
        return "".join(parts)

    def fixed(self, name: str, parent: str, child: str, matrix: np.ndarray) -> str:
        return (
            f'  <joint name="{name}" type="fixed">\n'
            f'    <parent link="{parent}"/>\n'
            f'    <child link="{child}"/>\n'
            f"    {self.origin(matrix)}\n"
            "  </joint>\n"
        )

    def moving(self, number: int, joint: Joint, origin: np.ndarray) -> str:
        if joint.is_revolute:
            lower, upper = math.radians(joint.min), math.radians(joint.max)
        else:
            lower, upper = self.metres(joint.min), self.metres(joint.max)
        return (
            f'  <joint name="joint{number}" type="{joint.type}">\n'
            f'    <parent link="link{number - 1}"/>\n'
            f'    <child link="link{number}"/>\n'
            f"    {self.origin(origin)}\n"
            '    <axis xyz="0 0 1"/>\n'
            f'    <limit lower="{_num(lower, 0.0)}" upper="{_num(upper, 0.0)}" '
            f'effort="{_num(PLACEHOLDER_EFFORT)}" velocity="{_num(PLACEHOLDER_VELOCITY)}"/>\n'
            "  </joint>\n"
        )

    def header(self) -> str:
        source = self.source
        name = json.dumps(_xml_safe(source.name), ensure_ascii=False).replace("--", "-\\u002d")
        return (
            '<?xml version="1.0" encoding="utf-8"?>\n'
            f"<!-- Exported by dhsim from robot {name}\n"
            f"     ({source.convention} D-H, lengths in {source.units}, angles in degrees).\n"
            "     Lengths here are in metres and angles in radians. Link linkI is the\n"
            "     modified D-H frame I, on joint I's axis; link world is dhsim's world\n"
            f"     frame (the floor is at z = {_num(-self.metres(source.base_height))}); "
            "link tool is the tool frame.\n"
            "     The value of jointI is dhsim's joint value q (theta = q + offset for\n"
            "     a revolute joint, d = q + offset for a prismatic one), in radians or\n"
            "     metres; the limits are dhsim's. effort and velocity limits are\n"
            f"     placeholders ({_num(PLACEHOLDER_EFFORT)} and "
            f"{_num(PLACEHOLDER_VELOCITY)}): dhsim knows no dynamics.\n"
            "     The visuals are plain cylinders along the links. -->\n"
        )


def _xml_safe(text: str) -> str:
    """``text`` with control characters escaped (:func:`printable`) and any
    character XML 1.0 cannot hold (U+FFFE, U+FFFF) written as ``\\uXXXX``."""
    return printable(text, also="\ufffe\uffff")


def dhsim_fields(robot: Robot) -> dict:
    """The whole robot as the JSON export's object (format ``dhsim-robot``
    version 1; :mod:`dhsim_tui.core.interop.export` documents it)."""

    def floats(values) -> list[float]:
        return [float(v) for v in values]

    return {
        "format": STORED_FORMAT,
        "version": STORED_VERSION,
        "name": robot.name,
        "units": {"length": robot.units, "angle": "deg"},
        "convention": robot.convention,
        "parameter_order": list(STORED_JOINT_FIELDS),
        "joint_value": STORED_JOINT_VALUE,
        "base": {
            "height": float(robot.base_height),
            "z": robot.base_z,
            "x": robot.base_x,
            "xyz": floats(robot.base_xyz),
            "rpy": floats(robot.base_rpy),
        },
        "tool": {"xyz": floats(robot.tool.xyz), "rpy": floats(robot.tool.rpy)},
        "joints": [
            {
                "type": j.type,
                **{name: float(getattr(j, name)) for name in STORED_JOINT_FIELDS},
                **{
                    name: float(getattr(j, name))
                    for name in STORED_OPTIONAL_JOINT_FIELDS
                    if getattr(j, name) is not None
                },
            }
            for j in robot.joints
        ],
        "poses": {name: floats(values) for name, values in robot.poses},
        "programs": programs_to_data(robot.programs),
    }


def stored_comment(robot: Robot) -> str:
    """The ``<!-- dhsim-robot 1: ... -->`` comment holding :func:`dhsim_fields`."""
    text = json.dumps(dhsim_fields(robot), ensure_ascii=False, allow_nan=False)
    text = text.replace("--", "-\\u002d").replace("\ufffe", "\\ufffe")
    text = text.replace("\uffff", "\\uffff")
    return (
        f"<!-- {DHSIM_COMMENT} {STORED_VERSION}: the robot as dhsim holds it, so that dhsim "
        "import gives it back\n"
        "     exactly while the joints below still match it (other tools ignore this).\n"
        f"     {text} -->\n"
    )


def to_urdf(robot: Robot) -> str:
    """The robot as a URDF serial chain (see the module's docstring)."""
    return _Urdf(robot).text()
