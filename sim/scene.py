"""One parameterised MJCF generator for the five garbage-can scenes of thesis Fig. 5.2.

World frame: the robot stands at negative x and faces +x ("forward"), +y is its left, +z up.
Every scene holds a table, one can whose front face lies in the plane x = 0, a yellow ball on
the table, a Cartesian arm (a hand on three position-controlled slide joints, i.e. a gantry
with force-limited actuators, plus a visual forearm) and the head camera ``head``.

Mechanisms (all contacts inside a can are excluded; parts move only through their joints):
- push lid (o1, o3): a tall lid hinged at its back-bottom edge; pushing its front face forward
  above the hinge tips it back, so the opening grows with the push distance; the push distance
  needed depends on how high the lid marker sits above the hinge.
- lift handle (o2, o4): a staple handle on the body's front face rides on a vertical slide
  geared to the lid hinge by an equality constraint (lid angle = gear x handle travel).
- pull handle (o5): the same handle on a slide toward the robot; lifting it is blocked.
Lids of handle cans are hinged at their back-top edge, so pushing their face presses them
shut against the joint limit. Hinge and slide friction (``frictionloss``) plus damping keep
every part where the robot left it. For chapter 4's continuous actions the hand can also keep
hold of the lid or the handle at the point it touches (an inactive ``connect`` equality per
part, switched on by ``GarbageWorld.hold``), so moving the hand back closes what it opened.

Run ``python -m sim.scene`` to (re)write the generated scenes to ``sim/assets/<can>.xml``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from sim.mjcf import LIGHTING
from sim.mjcf import box as _box
from sim.mjcf import fmt as _v
from sim.mjcf import look_at as _look_at

TABLE_TOP = 0.40
"""Height of the table surface (m)."""
WALL = 0.008
"""Thickness of the can walls (m)."""
CAP = 0.002
"""Height of the dark caps on the back and side walls (the rim seen from above is dark)."""
MARKER_SIZE: dict[str, tuple[float, float]] = {
    "body": (0.08, 0.04),
    "lid": (0.05, 0.02),
    "handle": (0.10, 0.03),
}
"""Visible (width along y, height along z) of each part's colour marker, in metres."""
MARKER_THICKNESS = 0.002
HANDLE_DEPTH = 0.01
"""Thickness of the handle bar along x (thesis: 10 cm x 3 cm x 1 cm)."""
HANDLE_GAP = 0.03
"""Free space between the handle bar and the can's front face (room for the hand)."""
HAND_RADIUS = 0.012
BALL_RADIUS = 0.025
GRIP_OFFSET = HAND_RADIUS + BALL_RADIUS + 0.001
"""The grasped ball sits this far in front (+x) of the hand centre."""
HOME = (-0.22, 0.20, 0.70)
"""Resting position of the hand: beside the can, out of the head camera's view of the can."""
ARM_RANGE = ((-0.42, 0.25), (-0.28, 0.45), (0.40, 1.05))
"""World-frame box (x, y, z bounds) the hand can reach."""
ARM_FORCE = 60.0
"""Force limit of each arm actuator (N): strong enough to open a lid, too weak to break one."""
HEAD_CAMERA_POS = (-0.75, 0.0, 0.87)
HEAD_CAMERA_TARGET = (0.08, 0.0, 0.67)
"""The head camera is the same in every scene: it looks at the can's upper front."""
HEAD_CAMERA_FOVY = 45.0

RGBA = {
    "body": "0.80 0.80 0.82 1",
    "lid": "0.93 0.93 0.90 1",
    "dark": "0.02 0.02 0.02 1",
    "red": "0.85 0.05 0.05 1",
    "blue": "0.05 0.15 0.85 1",
    "green": "0.10 0.72 0.10 1",
    "post": "0.60 0.60 0.62 1",
    "table": "0.76 0.72 0.66 1",
    "floor": "0.55 0.55 0.58 1",
    "wall": "0.85 0.87 0.90 1",
    "hand": "0.92 0.92 0.92 1",
    "arm": "0.68 0.68 0.70 1",
    "ball": "0.95 0.85 0.10 1",
}


@dataclass(frozen=True)
class CanSpec:
    """Geometry and mechanism of one garbage can (all lengths in metres)."""

    name: str
    parts: tuple[str, ...]
    functional: tuple[str, str]
    width: float
    depth: float
    height: float
    lid_height: float
    lid_marker_z: float
    gear: float = 0.0
    handle_drop: float = 0.13

    @property
    def rim(self) -> float:
        """World height of the rim (top of the body walls)."""
        return TABLE_TOP + self.height

    @property
    def mechanism(self) -> str:
        """Which of the three opening mechanisms this can has."""
        return {"lid": "push", "handle": self.functional[1]}[self.functional[0]]


CANS: dict[str, CanSpec] = {
    "o1": CanSpec("o1", ("body", "lid"), ("lid", "extend_arm"), 0.22, 0.30, 0.26, 0.13, 0.11),
    "o2": CanSpec(
        "o2", ("body", "lid", "handle"), ("handle", "lift_up"), 0.22, 0.30, 0.26, 0.03, 0.015,
        gear=7.0,
    ),
    "o3": CanSpec("o3", ("body", "lid"), ("lid", "extend_arm"), 0.20, 0.24, 0.24, 0.19, 0.17),
    "o4": CanSpec(
        "o4", ("body", "lid", "handle"), ("handle", "lift_up"), 0.24, 0.28, 0.28, 0.03, 0.015,
        gear=13.0,
    ),
    "o5": CanSpec(
        "o5", ("body", "lid", "handle"), ("handle", "contract_arm"), 0.22, 0.28, 0.27, 0.03,
        0.015, gear=6.0, handle_drop=0.07,
    ),
}
"""The five cans of thesis Fig. 5.2 / Table 5.3."""

HOLD = 'solreffriction="0.004 1" solimpfriction="0.99 0.999 0.001"'
"""Stiff dry friction on lid and handle joints, so parts hold still where they were left."""
SITE = 'size="0.003" rgba="0 0 0 0"'
"""Reference points (rim and lid front edges) are invisible."""
LID_RANGE = 1.75
"""Upper limit of every lid hinge (rad)."""
HOLDABLE = ("lid", "handle")
"""Parts the hand can keep hold of (a ball-joint constraint, off until ``hold``; thesis ch. 4)."""


def _body_xml(c: CanSpec) -> list[str]:
    """Static can body: bottom and four walls, a dark liner inside, the red marker in front."""
    w, d, h, t = c.width / 2, c.depth, c.height, WALL
    z0 = TABLE_TOP
    rows = ['<body name="can_body" pos="0 0 0">']
    rows.append(_box("body_bottom", (d / 2, 0, z0 + t / 2), (d / 2, w, t / 2), RGBA["body"]))
    rows.append(_box("body_front", (t / 2, 0, z0 + h / 2), (t / 2, w, h / 2), RGBA["body"]))
    hb = (h - CAP) / 2  # back and side walls stop under a dark cap, seen only when open
    rows.append(_box("body_back", (d - t / 2, 0, z0 + hb), (t / 2, w, hb), RGBA["body"]))
    rows.append(_box("cap_back", (d - t / 2, 0, z0 + h - CAP / 2), (t / 2, w, CAP / 2),
                     RGBA["dark"]))
    for side, sign in (("left", 1), ("right", -1)):
        y = sign * (w - t / 2)
        rows.append(_box(f"body_{side}", (d / 2, y, z0 + hb), (d / 2 - t, t / 2, hb),
                         RGBA["body"]))
        rows.append(_box(f"cap_{side}", (d / 2, y, z0 + h - CAP / 2), (d / 2 - t, t / 2, CAP / 2),
                         RGBA["dark"]))
    li = 0.001
    inner = (d / 2 - t - li, w - t - li)
    rows.append(_box("liner_bottom", (d / 2, 0, z0 + t + li), (inner[0], inner[1], li),
                     RGBA["dark"], collide=False))
    for name, cx, hx in (("liner_front", t + li, li), ("liner_back", d - t - li, li)):
        rows.append(_box(name, (cx, 0, z0 + h / 2 + t / 2), (hx, inner[1], h / 2 - t / 2 - li),
                         RGBA["dark"], collide=False))
    for name, sign in (("liner_left", 1), ("liner_right", -1)):
        rows.append(_box(name, (d / 2, sign * (w - t - li), z0 + h / 2 + t / 2),
                         (inner[0], li, h / 2 - t / 2 - li), RGBA["dark"], collide=False))
    mw, mh = MARKER_SIZE["body"]
    rows.append(_box("marker_body", (-MARKER_THICKNESS / 2, 0, z0 + 0.20 * h),
                     (MARKER_THICKNESS / 2, mw / 2, mh / 2), RGBA["red"], collide=False))
    rows.append(f'<site name="rim_front" pos="0 0 {z0 + h:.5g}" {SITE}/>')
    rows.append("</body>")
    return rows


def _lid_xml(c: CanSpec) -> list[str]:
    """Hinged lid; push lids hinge at the back-bottom edge, handle-can lids at the back-top."""
    w, d, lh = c.width / 2, c.depth, c.lid_height
    push = c.mechanism == "push"
    zb = 0.0 if push else -lh  # z of the lid's underside in the hinge frame
    hinge_z = c.rim if push else c.rim + lh
    mw, mh = MARKER_SIZE["lid"]
    rows = [f'<body name="lid" pos="{_v(d, 0, hinge_z)}">',
            f'<joint name="lid_hinge" type="hinge" axis="0 1 0" range="0 {LID_RANGE}" '
            f'limited="true" damping="1.0" frictionloss="0.25" armature="0.002" {HOLD}/>',
            _box("lid_shell", (-d / 2, 0, zb + lh / 2), (d / 2, w, lh / 2), RGBA["lid"],
                 extra=' mass="0.1"'),
            _box("lid_underside", (-d / 2, 0, zb - 0.0011), (d / 2 - 0.001, w - 0.001, 0.001),
                 RGBA["dark"], collide=False),
            _box("marker_lid", (-d - MARKER_THICKNESS / 2, 0, zb + c.lid_marker_z),
                 (MARKER_THICKNESS / 2, mw / 2, mh / 2), RGBA["blue"], collide=False),
            f'<site name="lid_front" pos="{_v(-d, 0, zb)}" {SITE}/>',
            "</body>"]
    return rows


def _handle_xml(c: CanSpec) -> list[str]:
    """Staple handle (green bar on two grey posts) on a slide geared to the lid hinge."""
    bw, bh = MARKER_SIZE["handle"]
    bx = -HANDLE_GAP - HANDLE_DEPTH / 2
    axis = "0 0 1" if c.mechanism == "lift_up" else "-1 0 0"
    travel = LID_RANGE / c.gear
    post_y = bw / 2 - 0.005
    rows = [f'<body name="handle" pos="{_v(bx, 0, c.rim - c.handle_drop)}">',
            f'<joint name="handle_slide" type="slide" axis="{axis}" range="0 {travel:.5g}" '
            f'limited="true" damping="2" frictionloss="6" armature="0.05" {HOLD}/>',
            _box("marker_handle", (0, 0, 0), (HANDLE_DEPTH / 2, bw / 2, bh / 2), RGBA["green"],
                 extra=' mass="0.05"')]
    for name, sign in (("handle_post_l", 1), ("handle_post_r", -1)):
        rows.append(_box(name, (HANDLE_DEPTH / 2 + HANDLE_GAP / 2, sign * post_y, 0),
                         (HANDLE_GAP / 2, 0.005, bh / 2), RGBA["post"], extra=' mass="0.01"'))
    rows.append("</body>")
    return rows


def build_mjcf(can: str) -> str:
    """The complete MJCF scene for one can, as text."""
    if can not in CANS:
        raise ValueError(f"unknown can {can!r}; expected one of {', '.join(CANS)}")
    c = CANS[can]
    (x0, x1), (y0, y1), (z0, z1) = ARM_RANGE
    hx, hy, hz = HOME
    parts = [f'<mujoco model="garbage_{can}">',
             '<compiler angle="radian" autolimits="true"/>',
             '<option timestep="0.002" integrator="implicitfast" cone="elliptic"/>',
             LIGHTING,
             '<default><geom friction="0.6 0.005 0.0001" solref="0.004 1"/></default>',
             "<worldbody>",
             '<light name="top" pos="0 0 2.2" dir="0 0 -1" diffuse="0.45 0.45 0.45" '
             'castshadow="false"/>',
             _box("floor", (0, 0, -0.005), (2, 2, 0.005), RGBA["floor"]),
             _box("table", (0.05, 0, TABLE_TOP / 2), (0.40, 0.55, TABLE_TOP / 2), RGBA["table"]),
             _box("backdrop", (1.2, 0, 1.0), (0.01, 2.0, 1.0), RGBA["wall"], collide=False),
             f'<camera name="head" pos="{_v(*HEAD_CAMERA_POS)}" fovy="{HEAD_CAMERA_FOVY}" '
             f'xyaxes="{_look_at(HEAD_CAMERA_POS, HEAD_CAMERA_TARGET)}"/>']
    parts += _body_xml(c)
    parts += _lid_xml(c)
    if "handle" in c.parts:
        parts += _handle_xml(c)
    parts += [f'<body name="hand" pos="{_v(hx, hy, hz)}" gravcomp="1">',
              f'<joint name="arm_x" type="slide" axis="1 0 0" range="{_v(x0 - hx, x1 - hx)}" '
              'damping="60"/>',
              f'<joint name="arm_y" type="slide" axis="0 1 0" range="{_v(y0 - hy, y1 - hy)}" '
              'damping="60"/>',
              f'<joint name="arm_z" type="slide" axis="0 0 1" range="{_v(z0 - hz, z1 - hz)}" '
              'damping="60"/>',
              f'<geom name="hand" type="sphere" size="{HAND_RADIUS}" mass="0.3" condim="1" '
              f'priority="1" rgba="{RGBA["hand"]}"/>',
              '<geom name="forearm" type="capsule" fromto="-0.012 0 0 -0.22 0 0.03" '
              f'size="0.009" rgba="{RGBA["arm"]}" contype="0" conaffinity="0" density="0"/>',
              "</body>",
              f'<body name="ball" pos="{_v(-0.10, 0.22, TABLE_TOP + BALL_RADIUS)}">',
              '<freejoint name="ball_free"/>',
              f'<geom name="ball" type="sphere" size="{BALL_RADIUS}" mass="0.03" '
              f'rgba="{RGBA["ball"]}" condim="4"/>',
              "</body>",
              "</worldbody>",
              "<contact>",
              '<exclude body1="hand" body2="ball"/>',
              '<exclude body1="can_body" body2="lid"/>']
    if "handle" in c.parts:
        parts += ['<exclude body1="can_body" body2="handle"/>',
                  '<exclude body1="lid" body2="handle"/>']
    parts.append("</contact>")
    parts.append("<equality>")
    parts.append(f'<weld name="grip" body1="hand" body2="ball" active="false" '
                 f'relpose="{_v(GRIP_OFFSET, 0, 0, 1, 0, 0, 0)}" solref="0.01 1"/>')
    if "handle" in c.parts:
        parts.append(f'<joint name="gear" joint1="lid_hinge" joint2="handle_slide" '
                     f'polycoef="0 {c.gear:.5g} 0 0 0" solref="0.005 1"/>')
    for part in HOLDABLE:  # anchors are set when the hand takes hold (GarbageWorld.hold)
        if part in c.parts:
            parts.append(f'<connect name="hold_{part}" body1="hand" body2="{part}" '
                         'anchor="0 0 0" active="false" solref="0.005 1"/>')
    parts.append("</equality>")
    parts.append("<actuator>")
    for axis, (lo, hi), home in zip("xyz", ARM_RANGE, HOME, strict=True):
        parts.append(f'<position name="act_{axis}" joint="arm_{axis}" kp="3000" '
                     f'ctrlrange="{_v(lo - home, hi - home)}" '
                     f'forcerange="{_v(-ARM_FORCE, ARM_FORCE)}"/>')
    parts.append("</actuator>")
    parts.append("</mujoco>")
    return "\n".join(parts) + "\n"


def asset_path(can: str) -> Path:
    """Where the generated scene of ``can`` is written."""
    return Path(__file__).parent / "assets" / f"{can}.xml"


def write_assets() -> list[Path]:
    """Write every generated scene under ``sim/assets/`` (for viewers and inspection)."""
    paths = []
    for can in CANS:
        path = asset_path(can)
        path.write_text(build_mjcf(can))
        paths.append(path)
    return paths


if __name__ == "__main__":
    for written in write_assets():
        print(written)
