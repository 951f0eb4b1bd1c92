"""One parameterised MJCF generator for garbage-can scenes (thesis Fig. 5.2 and beyond).

Cans are data: each is a ``CanSpec`` (``sim.canspec``) read from a YAML file by
``sim.canfile`` (the five thesis cans and two new mechanisms ship in ``sim/cans/``); ``CANS``
holds the thesis's o1..o5.

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
- slide lid (``slide``): a flat lid on a sideways slide, moved through a tab in front of its
  front edge that is geared to it like a lever; sweeping the tab one way opens it.
- pedal (``pedal``, thesis Fig. 4.1(d)): a foot plate low on the front, pressed down on a slide
  geared to the lid hinge.
Lids of handle and pedal cans are hinged at their back-top edge, so pushing their face presses them
shut against the joint limit. Parts that move though they open nothing (thesis Table 5.3) are
data too: a handle's play along some axes, and a can that slides back on the table under a
firm push, its parts riding on its body (``CanSpec.handle_play``, ``CanSpec.can_slide``).
Hinge and slide friction (``frictionloss``) plus damping keep every part where the robot left
it. For chapter 4's continuous actions the hand can also keep
hold of the lid or the handle at the point it touches (an inactive ``connect`` equality per
part, switched on by ``GarbageWorld.hold``), so moving the hand back closes what it opened.

Run ``python -m sim.scene`` to (re)write the generated scenes to ``sim/assets/<can>.xml``.
"""

from __future__ import annotations

from pathlib import Path

from ondisk import write_atomically
from sim.canfile import load_can, shipped_can_path
from sim.canspec import MARKER_SIZE, TABLE_TOP, CanSpec
from sim.mjcf import LIGHTING, box, fmt, look_at

WALL = 0.008
"""Thickness of the can walls (m)."""
CAP = 0.002
"""Height of the dark caps on the back and side walls (the rim seen from above is dark)."""
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
ARM_KP = 3000.0
"""Stiffness (N/m) of each arm actuator's position control."""
HEAD_CAMERA_POS = (-0.75, 0.0, 0.87)
HEAD_CAMERA_TARGET = (0.08, 0.0, 0.67)
"""The head camera is the same in every scene: it looks at the can's upper front."""
HEAD_CAMERA_FOVY = 45.0
CLOSE_CAMERA_SCALE = 0.6
CLOSE_CAMERA_POS = tuple(t + CLOSE_CAMERA_SCALE * (h - t)
                         for h, t in zip(HEAD_CAMERA_POS, HEAD_CAMERA_TARGET, strict=True))
"""Chapter 4's camera, ``close``: on the head camera's line of sight, 0.6 times as far from
its target, so it sees the opening from the same angle 2.8 times as large; a fully opened can
fills about 0.12-0.13 of its image, as the thesis's NAO bottom camera, 10-12 cm from the
can, saw it (eq. 4.19, Table 4.1). The head camera stays where the other chapters need it."""

RGBA = {
    "dark": "0.02 0.02 0.02 1",
    "red": "0.85 0.05 0.05 1",
    "blue": "0.05 0.15 0.85 1",
    "green": "0.10 0.72 0.10 1",
    "magenta": "0.80 0.10 0.75 1",
    "post": "0.60 0.60 0.62 1",
    "table": "0.76 0.72 0.66 1",
    "floor": "0.55 0.55 0.58 1",
    "wall": "0.85 0.87 0.90 1",
    "hand": "0.92 0.92 0.92 1",
    "arm": "0.68 0.68 0.70 1",
    "ball": "0.95 0.85 0.10 1",
}


def _load_cans() -> dict[str, CanSpec]:
    """The five thesis cans from their files (sim/cans/o1.yaml .. o5.yaml)."""
    return {name: load_can(shipped_can_path(name)) for name in ("o1", "o2", "o3", "o4", "o5")}


HOLD = 'solreffriction="0.004 1" solimpfriction="0.99 0.999 0.001"'
"""Stiff dry friction on lid and handle joints, so parts hold still where they were left."""
SITE = 'size="0.003" rgba="0 0 0 0"'
"""Reference points (rim and lid front edges) are invisible."""
LID_RANGE = 1.75
"""Upper limit of every lid hinge (rad)."""
HOLD_SOLREF = (0.005, 1.0)
"""solref (time constant s, damping ratio) of the hand's hold on a part."""
HOLDABLE = ("lid", "handle")
"""Parts the hand can keep hold of (a ball-joint constraint, off until ``hold``; thesis ch. 4)."""
SLIDE_TRAVEL = 0.75
"""How far a sliding lid can slide, as a fraction of the can's width."""
TAB_DEPTH = 0.03
"""Depth (x) of the tab in front of a sliding lid, which carries the lid's marker ..."""
TAB_GAP = 0.005
"""... and the space between the tab and the can's front face."""
TAB_HALF_HEIGHT = 0.03
"""Half the tab's height: well above and below the hand's radius, so the hand cannot ride
over it."""
PLAY_AXES = {"x": "1 0 0", "y": "0 1 0", "z": "0 0 1"}
"""Directions of a handle's play (``CanSpec.handle_play``)."""
PLAY_FRICTION = 4.0
"""Friction (N) of a handle's play: above the handle's weight, so it stays where it was left,
far below the arm's force, so a push moves it."""
CAN_SLIDE_FRICTION = 25.0
"""Friction (N) of a sliding can (``CanSpec.can_slide``): a push that opens a lid is far
weaker; one against a part that cannot move (the body, a closed lid pressed shut) reaches the
arm's ``ARM_FORCE`` and slides the can."""
PEDAL_DEPTH = 0.05
"""Depth (x) of the pedal's foot plate."""
PEDAL_CLEARANCE = 0.005
"""Space left between the pressed-down pedal and the table."""


def _rgba(colour: tuple[float, float, float]) -> str:
    """An MJCF rgba attribute of an opaque paint colour (two decimals)."""
    return " ".join(f"{x:.2f}" for x in colour) + " 1"


def _body_xml(c: CanSpec) -> list[str]:
    """Static can body: bottom and four walls, a dark liner inside, the red marker in front."""
    w, d, h, t = c.width / 2, c.depth, c.height, WALL
    z0 = TABLE_TOP
    paint = _rgba(c.body_colour)
    rows = ['<body name="can_body" pos="0 0 0">']
    rows.append(box("body_bottom", (d / 2, 0, z0 + t / 2), (d / 2, w, t / 2), paint))
    rows.append(box("body_front", (t / 2, 0, z0 + h / 2), (t / 2, w, h / 2), paint))
    hb = (h - CAP) / 2  # back and side walls stop under a dark cap, seen only when open
    rows.append(box("body_back", (d - t / 2, 0, z0 + hb), (t / 2, w, hb), paint))
    rows.append(box("cap_back", (d - t / 2, 0, z0 + h - CAP / 2), (t / 2, w, CAP / 2),
                     RGBA["dark"]))
    for side, sign in (("left", 1), ("right", -1)):
        y = sign * (w - t / 2)
        rows.append(box(f"body_{side}", (d / 2, y, z0 + hb), (d / 2 - t, t / 2, hb),
                         paint))
        rows.append(box(f"cap_{side}", (d / 2, y, z0 + h - CAP / 2), (d / 2 - t, t / 2, CAP / 2),
                         RGBA["dark"]))
    li = 0.001
    inner = (d / 2 - t - li, w - t - li)
    rows.append(box("liner_bottom", (d / 2, 0, z0 + t + li), (inner[0], inner[1], li),
                     RGBA["dark"], collide=False))
    for name, cx, hx in (("liner_front", t + li, li), ("liner_back", d - t - li, li)):
        rows.append(box(name, (cx, 0, z0 + h / 2 + t / 2), (hx, inner[1], h / 2 - t / 2 - li),
                         RGBA["dark"], collide=False))
    for name, sign in (("liner_left", 1), ("liner_right", -1)):
        rows.append(box(name, (d / 2, sign * (w - t - li), z0 + h / 2 + t / 2),
                         (inner[0], li, h / 2 - t / 2 - li), RGBA["dark"], collide=False))
    mw, mh = MARKER_SIZE["body"]
    rows.append(box("marker_body", (-MARKER_THICKNESS / 2, 0, z0 + 0.20 * h),
                     (MARKER_THICKNESS / 2, mw / 2, mh / 2), RGBA["red"], collide=False))
    rows.append(f'<site name="rim_front" pos="0 0 {z0 + h:.5g}" {SITE}/>')
    rows.append("</body>")
    return rows


def _lid_xml(c: CanSpec) -> list[str]:
    """Hinged lid; push lids hinge at the back-bottom edge, the others at the back-top."""
    if c.mechanism == "slide_lid":
        return _slide_lid_xml(c)
    w, d, lh = c.width / 2, c.depth, c.lid_height
    push = c.mechanism == "push_lid"
    zb = 0.0 if push else -lh  # z of the lid's underside in the hinge frame
    hinge_z = c.rim if push else c.rim + lh
    mw, mh = MARKER_SIZE["lid"]
    rows = [f'<body name="lid" pos="{fmt(d, 0, hinge_z)}">',
            f'<joint name="lid_hinge" type="hinge" axis="0 1 0" range="0 {LID_RANGE}" '
            f'limited="true" damping="1.0" frictionloss="0.25" armature="0.002" {HOLD}/>',
            box("lid_shell", (-d / 2, 0, zb + lh / 2), (d / 2, w, lh / 2), _rgba(c.lid_colour),
                 extra=' mass="0.1"'),
            box("lid_underside", (-d / 2, 0, zb - 0.0011), (d / 2 - 0.001, w - 0.001, 0.001),
                 RGBA["dark"], collide=False),
            box("marker_lid", (-d - MARKER_THICKNESS / 2, 0, zb + c.lid_marker_z),
                 (MARKER_THICKNESS / 2, mw / 2, mh / 2), RGBA["blue"], collide=False),
            f'<site name="lid_front" pos="{fmt(-d, 0, zb)}" {SITE}/>',
            "</body>"]
    return rows


def _slide_lid_xml(c: CanSpec) -> list[str]:
    """A flat lid on a sideways slide, moved through a tab in front of its front edge: the tab
    (which carries the lid's blue marker and which the hand sweeps) slides too, geared to the
    lid like a lever (the lid travels ``gear`` times as far). The lid's front-centre starts at
    the rim's front-centre, so the opening (the distance between the two) is how far it slid."""
    w, d, lh = c.width / 2, c.depth, c.lid_height
    mw, mh = MARKER_SIZE["lid"]
    axis = f"0 {1 if c.slide == 'left' else -1} 0"
    travel = SLIDE_TRAVEL * c.width
    paint = _rgba(c.lid_colour)
    return [f'<body name="lid" pos="{fmt(0, 0, c.rim)}">',
            f'<joint name="lid_slide" type="slide" axis="{axis}" range="0 {travel:.5g}" '
            f'limited="true" damping="2" frictionloss="3" armature="0.02" {HOLD}/>',
            box("lid_shell", (d / 2, 0, lh / 2), (d / 2, w, lh / 2), paint, extra=' mass="0.1"'),
            f'<site name="lid_front" pos="0 0 0" {SITE}/>',
            "</body>",
            f'<body name="lid_tab" pos="{fmt(-TAB_GAP - TAB_DEPTH / 2, 0, c.rim + lh / 2)}">',
            f'<joint name="tab_slide" type="slide" axis="{axis}" range="0 {travel / c.gear:.5g}" '
            f'limited="true" damping="2" frictionloss="3" armature="0.02" {HOLD}/>',
            box("tab", (0, 0, 0), (TAB_DEPTH / 2, mw / 2, TAB_HALF_HEIGHT), paint,
                 extra=' mass="0.01"'),
            box("marker_lid", (-TAB_DEPTH / 2 - MARKER_THICKNESS / 2, 0, 0),
                 (MARKER_THICKNESS / 2, mw / 2, mh / 2), RGBA["blue"], collide=False),
            "</body>"]


def _pedal_xml(c: CanSpec) -> list[str]:
    """A magenta foot plate low on the front, left of the body marker, on a slide pressed
    down and geared to the lid hinge; it can travel until it nearly reaches the table."""
    pw, ph = MARKER_SIZE["pedal"]
    x = -HANDLE_GAP - PEDAL_DEPTH / 2
    y = c.width / 2 - pw / 2 - 0.015
    travel = min(LID_RANGE / c.gear, c.pedal_z - ph / 2 - PEDAL_CLEARANCE)
    rows = [f'<body name="pedal" pos="{fmt(x, y, TABLE_TOP + c.pedal_z)}">',
            f'<joint name="pedal_slide" type="slide" axis="0 0 -1" range="0 {travel:.5g}" '
            f'limited="true" damping="2" frictionloss="6" armature="0.05" {HOLD}/>',
            box("marker_pedal", (0, 0, 0), (PEDAL_DEPTH / 2, pw / 2, ph / 2), RGBA["magenta"],
                 extra=' mass="0.05"'),
            box("pedal_post", (PEDAL_DEPTH / 2 + HANDLE_GAP / 2, 0, 0),
                 (HANDLE_GAP / 2, 0.005, ph / 2), RGBA["post"], extra=' mass="0.01"'),
            "</body>"]
    return rows


def _handle_xml(c: CanSpec) -> list[str]:
    """Staple handle (green bar on two grey posts) on a slide geared to the lid hinge."""
    bw, bh = MARKER_SIZE["handle"]
    bx = -HANDLE_GAP - HANDLE_DEPTH / 2
    axis = "0 0 1" if c.mechanism == "lift_handle" else "-1 0 0"
    travel = LID_RANGE / c.gear
    post_y = bw / 2 - 0.005
    rows = [f'<body name="handle" pos="{fmt(bx, 0, c.rim - c.handle_drop)}">',
            f'<joint name="handle_slide" type="slide" axis="{axis}" range="0 {travel:.5g}" '
            f'limited="true" damping="2" frictionloss="6" armature="0.05" {HOLD}/>']
    for name in c.handle_play:  # play: the handle gives a little, geared to nothing
        rows.append(f'<joint name="handle_play_{name}" type="slide" axis="{PLAY_AXES[name]}" '
                    f'range="{fmt(-c.play_travel, c.play_travel)}" limited="true" damping="2" '
                    f'frictionloss="{PLAY_FRICTION:g}" armature="0.05" {HOLD}/>')
    rows.append(box("marker_handle", (0, 0, 0), (HANDLE_DEPTH / 2, bw / 2, bh / 2),
                    RGBA["green"], extra=' mass="0.05"'))
    for name, sign in (("handle_post_l", 1), ("handle_post_r", -1)):
        rows.append(box(name, (HANDLE_DEPTH / 2 + HANDLE_GAP / 2, sign * post_y, 0),
                         (HANDLE_GAP / 2, 0.005, bh / 2), RGBA["post"], extra=' mass="0.01"'))
    rows.append("</body>")
    return rows


def build_mjcf(can: str | CanSpec) -> str:
    """The complete MJCF scene for one can (a CanSpec, or the name of a thesis can), as text."""
    if isinstance(can, CanSpec):
        c = can
    elif can in thesis_cans():
        c = thesis_cans()[can]
    else:
        raise ValueError(f"unknown can {can!r}; expected one of {', '.join(thesis_cans())}")
    (x0, x1), (y0, y1), (z0, z1) = ARM_RANGE
    hx, hy, hz = HOME
    parts = [f'<mujoco model="garbage_{c.name}">',
             '<compiler angle="radian" autolimits="true"/>',
             '<option timestep="0.002" integrator="implicitfast" cone="elliptic"/>',
             LIGHTING,
             '<default><geom friction="0.6 0.005 0.0001" solref="0.004 1"/></default>',
             "<worldbody>",
             '<light name="top" pos="0 0 2.2" dir="0 0 -1" diffuse="0.45 0.45 0.45" '
             'castshadow="false"/>',
             box("floor", (0, 0, -0.005), (2, 2, 0.005), RGBA["floor"]),
             box("table", (0.05, 0, TABLE_TOP / 2), (0.40, 0.55, TABLE_TOP / 2), RGBA["table"]),
             box("backdrop", (1.2, 0, 1.0), (0.01, 2.0, 1.0), RGBA["wall"], collide=False),
             f'<camera name="head" pos="{fmt(*HEAD_CAMERA_POS)}" fovy="{HEAD_CAMERA_FOVY}" '
             f'xyaxes="{look_at(HEAD_CAMERA_POS, HEAD_CAMERA_TARGET)}"/>',
             f'<camera name="close" pos="{fmt(*CLOSE_CAMERA_POS)}" fovy="{HEAD_CAMERA_FOVY}" '
             f'xyaxes="{look_at(CLOSE_CAMERA_POS, HEAD_CAMERA_TARGET)}"/>']
    body = _body_xml(c)
    moving = _lid_xml(c)
    if "handle" in c.parts:
        moving += _handle_xml(c)
    if "pedal" in c.parts:
        moving += _pedal_xml(c)
    if c.can_slide > 0:  # the parts ride on the sliding body (same coordinates: it is at 0)
        parts += [body[0], f'<joint name="can_slide" type="slide" axis="1 0 0" '
                  f'range="0 {c.can_slide:.5g}" limited="true" damping="20" '
                  f'frictionloss="{CAN_SLIDE_FRICTION:g}" armature="0.1" {HOLD}/>',
                  *body[1:-1], *moving, body[-1]]
    else:
        parts += body + moving
    parts += [f'<body name="hand" pos="{fmt(hx, hy, hz)}" gravcomp="1">',
              f'<joint name="arm_x" type="slide" axis="1 0 0" range="{fmt(x0 - hx, x1 - hx)}" '
              'damping="60"/>',
              f'<joint name="arm_y" type="slide" axis="0 1 0" range="{fmt(y0 - hy, y1 - hy)}" '
              'damping="60"/>',
              f'<joint name="arm_z" type="slide" axis="0 0 1" range="{fmt(z0 - hz, z1 - hz)}" '
              'damping="60"/>',
              f'<geom name="hand" type="sphere" size="{HAND_RADIUS}" mass="0.3" condim="1" '
              f'priority="1" rgba="{RGBA["hand"]}"/>',
              '<geom name="forearm" type="capsule" fromto="-0.012 0 0 -0.22 0 0.03" '
              f'size="0.009" rgba="{RGBA["arm"]}" contype="0" conaffinity="0" density="0"/>',
              "</body>",
              f'<body name="ball" pos="{fmt(-0.10, 0.22, TABLE_TOP + BALL_RADIUS)}">',
              '<freejoint name="ball_free"/>',
              f'<geom name="ball" type="sphere" size="{BALL_RADIUS}" mass="0.03" '
              f'rgba="{RGBA["ball"]}" condim="4"/>',
              "</body>",
              "</worldbody>",
              "<contact>",
              '<exclude body1="hand" body2="ball"/>',
              '<exclude body1="can_body" body2="lid"/>']
    if c.can_slide > 0:  # the sliding can stands on the table without rubbing on it
        parts.append('<exclude body1="world" body2="can_body"/>')
    for extra in ("handle", "pedal", "lid_tab"):
        if extra in c.parts or (extra == "lid_tab" and c.mechanism == "slide_lid"):
            parts += [f'<exclude body1="can_body" body2="{extra}"/>',
                      f'<exclude body1="lid" body2="{extra}"/>']
    parts.append("</contact>")
    parts.append("<equality>")
    parts.append(f'<weld name="grip" body1="hand" body2="ball" active="false" '
                 f'relpose="{fmt(GRIP_OFFSET, 0, 0, 1, 0, 0, 0)}" solref="0.01 1"/>')
    if c.geared_joint is not None:
        parts.append(f'<joint name="gear" joint1="{c.lid_joint}" joint2="{c.geared_joint}" '
                     f'polycoef="0 {c.gear:.5g} 0 0 0" solref="0.005 1"/>')
    for part in HOLDABLE:  # anchors are set when the hand takes hold (GarbageWorld.hold)
        if part in c.parts:
            parts.append(f'<connect name="hold_{part}" body1="hand" body2="{part}" '
                         f'anchor="0 0 0" active="false" solref="{fmt(*HOLD_SOLREF)}"/>')
    parts.append("</equality>")
    parts.append("<actuator>")
    for axis, (lo, hi), home in zip("xyz", ARM_RANGE, HOME, strict=True):
        parts.append(f'<position name="act_{axis}" joint="arm_{axis}" kp="{ARM_KP:g}" '
                     f'ctrlrange="{fmt(lo - home, hi - home)}" '
                     f'forcerange="{fmt(-ARM_FORCE, ARM_FORCE)}"/>')
    parts.append("</actuator>")
    parts.append("</mujoco>")
    return "\n".join(parts) + "\n"


def asset_path(can: str) -> Path:
    """Where the generated scene of ``can`` is written."""
    return Path(__file__).parent / "assets" / f"{can}.xml"


def thesis_cans() -> dict[str, CanSpec]:
    """The five thesis cans o1..o5 of Fig. 5.2 / Table 5.3, read from their files once."""
    if "CANS" not in globals():
        globals()["CANS"] = _load_cans()
    return globals()["CANS"]


def __getattr__(name: str) -> object:
    """``CANS`` (the five thesis cans) is read from their files on first use (PEP 562)."""
    if name == "CANS":
        return thesis_cans()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def write_assets() -> list[Path]:
    """Write every generated scene under ``sim/assets/`` (for viewers and inspection)."""
    paths = []
    for can in thesis_cans():
        path = asset_path(can)
        write_atomically(path, build_mjcf(can))
        paths.append(path)
    return paths


if __name__ == "__main__":
    for written in write_assets():
        print(written)
