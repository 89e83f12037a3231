"""URDF to MJCF: the MuJoCo model of a robot that osrl describes (no ``mujoco`` import here).

``mjcf_from_urdf`` turns the URDF that ``osrl robot --robot NAME --urdf`` or ``Robot.to_urdf()``
prints (or any URDF of revolute, continuous and fixed joints) into MJCF text:

- one body per moving link, its frame where the URDF puts it (``pos``, ``quat``), a hinge joint
  on the URDF axis with the URDF's ``damping`` (osrl's viscous friction), ``friction`` as
  MuJoCo's ``frictionloss`` and ``limit lower/upper`` as the joint range;
- fixed joints folded into their parent, as osrl's URDF import does: their inertia is added to
  the parent's and their frame becomes a site (the end effector ``ee_link`` of osrl's exports);
- a site at every link frame, named after the link;
- one ``motor`` per joint (gear 1: the control is the joint torque, N·m) limited to the URDF's
  ``effort``;
- no contacts, gravity 9.81 m/s² along −z, the given time step and integrator.

Inertias MuJoCo cannot hold. MuJoCo accepts only physically consistent bodies (a positive mass
and principal moments that are positive and satisfy the triangle inequality). Identified
parameters need not be: every link of ``sarcos7`` (its identified base parameters, with two
massless proximal links) fails the check, and no redistribution of mass along the joint axes
between neighbouring links makes them consistent (the best such regrouping leaves a pseudo-
inertia eigenvalue of −0.0115 kg·m²; see ROBOT_PROTOCOL.md). For such a link the MJCF carries a
valid placeholder inertial and the exact values in ``<custom><numeric name="osrl_inertial:LINK">``
(mass, centre of mass, inertia about it); ``osrl.mujoco.load_model`` compiles the MJCF and writes
the exact values into the compiled model. Loaded any other way, such a model has the placeholder
dynamics.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

import numpy as np

from .inertia import Inertial, mujoco_accepts, quat_from_matrix, rpy_matrix

__all__ = ["mjcf_from_urdf", "builtin_mjcf", "INERTIAL_PREFIX"]

INERTIAL_PREFIX = "osrl_inertial:"
"""Name prefix of the custom numerics that hold exact inertials (see the module docs)."""


def _num(v: float) -> str:
    """The shortest decimal that reads back as the same float."""
    return repr(float(v))


def _vec(v) -> str:
    return " ".join(_num(a) for a in v)


def _floats(node: Optional[ET.Element], attr: str, n: int, default: Optional[List[float]]) -> List[float]:
    text = None if node is None else node.get(attr)
    if text is None:
        if default is None:
            raise ValueError(f"URDF: <{node.tag if node is not None else '?'}> lacks '{attr}'")
        return list(default)
    vals = [float(s) for s in text.split()]
    if len(vals) != n or not all(np.isfinite(vals)):
        raise ValueError(f"URDF: <{node.tag} {attr}=\"{text}\"> needs {n} finite numbers")
    return vals


def _pose(node: ET.Element) -> Tuple[np.ndarray, np.ndarray]:
    """The ``<origin xyz rpy>`` child of ``node`` as (rotation, translation)."""
    o = node.find("origin")
    xyz = _floats(o, "xyz", 3, [0.0, 0.0, 0.0])
    rpy = _floats(o, "rpy", 3, [0.0, 0.0, 0.0])
    return rpy_matrix(*rpy), np.array(xyz)


def _inertial(link: ET.Element) -> Inertial:
    """A link's ``<inertial>`` about its own frame (zero when absent)."""
    node = link.find("inertial")
    if node is None:
        return Inertial.zero()
    rot, com = _pose(node)
    mass_node = node.find("mass")
    inertia_node = node.find("inertia")
    if mass_node is None or inertia_node is None:
        raise ValueError(f"URDF: link '{link.get('name')}': <inertial> needs <mass> and <inertia>")
    (mass,) = _floats(mass_node, "value", 1, None)
    keys = ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"]
    xx, xy, xz, yy, yz, zz = (_floats(inertia_node, k, 1, None)[0] for k in keys)
    local = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
    return Inertial.from_com(mass, com, rot @ local @ rot.T)


@dataclass
class _Body:
    """A moving link: its joint, pose in the parent body, inertial and what hangs on it."""

    link: str
    joint: ET.Element
    rot: np.ndarray
    pos: np.ndarray
    inertial: Inertial
    sites: List[Tuple[str, np.ndarray, np.ndarray]] = field(default_factory=list)
    children: List["_Body"] = field(default_factory=list)


class _Urdf:
    """The parsed tree: links by name, joints by parent link."""

    def __init__(self, text: str):
        try:
            root = ET.fromstring(text)
        except ET.ParseError as e:
            raise ValueError(f"URDF: malformed XML: {e}") from None
        if root.tag != "robot":
            raise ValueError(f"URDF: the root element is <{root.tag}>, expected <robot>")
        self.name = root.get("name", "robot")
        self.links: Dict[str, ET.Element] = {l.get("name"): l for l in root.findall("link")}
        self.children: Dict[str, List[ET.Element]] = {}
        child_links = set()
        for j in root.findall("joint"):
            kind = j.get("type")
            if kind not in ("revolute", "continuous", "fixed"):
                raise ValueError(f"URDF: joint '{j.get('name')}' of type {kind!r}: only revolute, continuous and fixed joints are supported")
            parent, child = j.find("parent").get("link"), j.find("child").get("link")
            if child not in self.links or parent not in self.links:
                raise ValueError(f"URDF: joint '{j.get('name')}' names a link that is not defined")
            self.children.setdefault(parent, []).append(j)
            child_links.add(child)
        roots = [n for n in self.links if n not in child_links]
        if len(roots) != 1:
            raise ValueError(f"URDF: expected one root link, found {roots}")
        self.root = roots[0]

    def body(self, joint: ET.Element) -> _Body:
        """The body of a moving joint's child link, fixed descendants folded in."""
        rot, pos = _pose(joint)
        link = joint.find("child").get("link")
        b = _Body(link, joint, rot, pos, _inertial(self.links[link]))
        b.sites.append((link, np.eye(3), np.zeros(3)))
        self._fold(b, link, np.eye(3), np.zeros(3))
        return b

    def _fold(self, b: _Body, link: str, rot: np.ndarray, pos: np.ndarray) -> None:
        """Adds the joints below ``link`` (at ``rot``, ``pos`` in ``b``'s frame) to ``b``."""
        for j in self.children.get(link, []):
            if j.get("type") == "fixed":
                jr, jp = _pose(j)
                r, p = rot @ jr, rot @ jp + pos
                child = j.find("child").get("link")
                b.inertial = b.inertial + _inertial(self.links[child]).transformed(r, p)
                b.sites.append((child, r, p))
                self._fold(b, child, r, p)
            else:
                sub = self.body(j)
                sub.rot, sub.pos = rot @ sub.rot, rot @ sub.pos + pos
                b.children.append(sub)

    def bodies(self) -> List[_Body]:
        """The bodies on the world (links fixed to the root are part of the world)."""
        out: List[_Body] = []

        def walk(link: str, rot: np.ndarray, pos: np.ndarray) -> None:
            for j in self.children.get(link, []):
                if j.get("type") == "fixed":
                    jr, jp = _pose(j)
                    walk(j.find("child").get("link"), rot @ jr, rot @ jp + pos)
                else:
                    b = self.body(j)
                    b.rot, b.pos = rot @ b.rot, rot @ b.pos + pos
                    out.append(b)

        walk(self.root, np.eye(3), np.zeros(3))
        if not out:
            raise ValueError("URDF: no revolute or continuous joint")
        return out


def _joint_xml(j: ET.Element, joint_limits: bool) -> str:
    axis = _floats(j.find("axis"), "xyz", 3, [1.0, 0.0, 0.0])
    dyn = j.find("dynamics")
    damping = _floats(dyn, "damping", 1, [0.0])[0]
    friction = _floats(dyn, "friction", 1, [0.0])[0]
    attrs = f'name="{j.get("name")}" type="hinge" axis="{_vec(axis)}"'
    if j.get("type") == "revolute" and joint_limits:
        lim = j.find("limit")
        lo, hi = _floats(lim, "lower", 1, None)[0], _floats(lim, "upper", 1, None)[0]
        attrs += f' limited="true" range="{_num(lo)} {_num(hi)}"'
    else:
        attrs += ' limited="false"'
    return f'<joint {attrs} damping="{_num(damping)}" frictionloss="{_num(friction)}"/>'


def _inertial_xml(b: _Body, custom: List[str]) -> str:
    """The body's ``<inertial>``: exact when MuJoCo accepts it, else a placeholder with the
    exact values in a custom numeric (module docs)."""
    inertial = b.inertial
    if mujoco_accepts(inertial):
        i = inertial.inertia_com
        full = [i[0, 0], i[1, 1], i[2, 2], i[0, 1], i[0, 2], i[1, 2]]
        return f'<inertial pos="{_vec(inertial.com)}" mass="{_num(inertial.mass)}" fullinertia="{_vec(full)}"/>'
    i = inertial.inertia_com
    data = [inertial.mass, *inertial.com, i[0, 0], i[1, 1], i[2, 2], i[0, 1], i[0, 2], i[1, 2]]
    custom.append(f'<numeric name="{INERTIAL_PREFIX}{b.link}" size="10" data="{_vec(data)}"/>')
    return (f'<!-- not physically consistent: placeholder; exact values in numeric '
            f'"{INERTIAL_PREFIX}{b.link}" (osrl.mujoco.load_model) -->\n'
            f'<inertial pos="{_vec(inertial.com)}" mass="1e-3" diaginertia="1e-6 1e-6 1e-6"/>')


def _body_xml(b: _Body, joint_limits: bool, custom: List[str], indent: str) -> List[str]:
    quat = quat_from_matrix(b.rot)
    out = [f'{indent}<body name="{b.link}" pos="{_vec(b.pos)}" quat="{_vec(quat)}">']
    inner = indent + "  "
    out.append(inner + _joint_xml(b.joint, joint_limits))
    out.extend(inner + line for line in _inertial_xml(b, custom).split("\n"))
    for name, rot, pos in b.sites:
        out.append(f'{inner}<site name="{name}" pos="{_vec(pos)}" quat="{_vec(quat_from_matrix(rot))}" size="0.01"/>')
    # Visual links (no mass, no contacts): from this frame to each child's and each site's.
    ends = [c.pos for c in b.children] + [pos for _, _, pos in b.sites[1:]]
    for end in ends:
        if np.linalg.norm(end) > 1e-9:
            out.append(f'{inner}<geom type="capsule" fromto="0 0 0 {_vec(end)}" size="0.02" '
                       'contype="0" conaffinity="0" group="1" mass="0"/>')
    for c in b.children:
        out.extend(_body_xml(c, joint_limits, custom, inner))
    out.append(f"{indent}</body>")
    return out


def _motors(bodies: List[_Body]) -> List[str]:
    out = []
    stack = list(bodies)
    while stack:
        b = stack.pop(0)
        name = b.joint.get("name")
        lim = b.joint.find("limit")
        effort = None if lim is None or lim.get("effort") is None else _floats(lim, "effort", 1, None)[0]
        rng = '' if effort is None else f' ctrllimited="true" ctrlrange="{_num(-effort)} {_num(effort)}"'
        out.append(f'    <motor name="{name}" joint="{name}" gear="1"{rng}/>')
        stack = b.children + stack
    return out


def mjcf_from_urdf(urdf: str, *, timestep: float = 0.001, integrator: str = "RK4",
                   joint_limits: bool = True) -> str:
    """The MJCF text of the robot in ``urdf`` (see the module docs for the mapping).

    ``timestep`` is MuJoCo's step (s); ``integrator`` one of MuJoCo's (``"RK4"``, ``"Euler"``,
    ``"implicit"``, ``"implicitfast"``); ``joint_limits=False`` leaves the joints unlimited.
    Raises ``ValueError`` on a malformed URDF or an unsupported joint type.
    """
    if not (np.isfinite(timestep) and timestep > 0):
        raise ValueError(f"timestep = {timestep}: must be a positive number of seconds")
    tree = _Urdf(urdf)
    bodies = tree.bodies()
    custom: List[str] = []
    body_lines: List[str] = []
    for b in bodies:
        body_lines.extend(_body_xml(b, joint_limits, custom, "    "))
    lines = [
        f'<mujoco model="{tree.name}">',
        "  <!-- made by osrl.mujoco.mjcf_from_urdf; load with osrl.mujoco.load_model -->",
        '  <compiler angle="radian" inertiafromgeom="false" autolimits="false"/>',
        f'  <option timestep="{_num(timestep)}" integrator="{integrator}" gravity="0 0 -9.81">',
        '    <flag contact="disable"/>',
        "  </option>",
        "  <worldbody>",
        *body_lines,
        "  </worldbody>",
        "  <actuator>",
        *_motors(bodies),
        "  </actuator>",
    ]
    if custom:
        lines += ["  <custom>", *("    " + c for c in custom), "  </custom>"]
    lines.append("</mujoco>")
    return "\n".join(lines) + "\n"


def builtin_mjcf(name: str, **kwargs) -> str:
    """The MJCF text of a built-in robot (``osrl.Robot.builtins()``), from its URDF export;
    keyword arguments as ``mjcf_from_urdf``."""
    from .. import Robot

    return mjcf_from_urdf(Robot.builtin(name).to_urdf(), **kwargs)
