"""The navigation world of thesis §3.5.1-3.5.7 (Fig. 3.3): a robot, two boxes and a destination.

World frame: the table's near-right corner is at x = 0, y = -0.3; the robot faces +x, +y is
its left, +z up. The table area is 0.75 m x 0.6 m (x by y), its top ``TABLE_TOP`` above the
floor. The robot is a stand-in for the NAO: an upright block on one small round foot, moved by
force-limited position actuators on two horizontal slides (walking; ``D_WALK`` = 0.15 m per
step along one of four lanes) and free to fall on a third, vertical slide: walking over the
table edge takes the foot off the table and the robot really drops (the trial ends).

Two boxes side by side block every lane: one light (it slides when pushed), one heavy (40 kg:
the robot's 20 N cannot overcome its friction, so a push really fails in the physics). Each
carries a colour marker in the middle of its top face (§3.5.1): blue on the movable box, red on
the other. ``exchanged`` swaps their places (§3.5.7: the unmovable box is on the left during
the first ten trials, on the right after). The destination is a line ``DESTINATION_AHEAD``
(0.4 m) ahead of the robot's start; reaching within ``D_DST`` of it is the goal (eq. 3.14).

Walking is guarded (the robot stops when it touches a box, as its sonar would tell it: §3.5.3);
pushing is not (it leans in with its full force). Run ``python -m sim.navigation`` to print the
generated MJCF.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from sim.base import RenderedWorld
from sim.mjcf import LIGHTING, box, fmt, look_at

TABLE_TOP = 0.40
"""Height of the table surface above the floor (m)."""
TABLE_X = (0.0, 0.75)
TABLE_Y = (-0.30, 0.30)
"""The table area (m): 0.75 m along the walking direction by 0.6 m across (§3.5.7)."""
D_WALK = 0.15
"""Length of one walk or push step (m), d_walk of §3.5.7."""
LANES = (-0.225, -0.075, 0.075, 0.225)
"""The four lanes (y, m) the robot can stand in; a step sideways from the outer ones falls off."""
START_X = 0.10
"""x (m) of the robot's centre at the start of every trial."""
START_LANE = LANES[0]
"""The robot's default start: the right-most lane, facing the box on the right (§3.5.8's
comparison starts there after the exchange); ``reset(lane=...)`` starts it in any lane
(§3.5.7: "anywhere on one side of the area")."""
DESTINATION_AHEAD = 0.40
"""The destination lies this far ahead of the start (§3.5.7)."""
DESTINATION_X = START_X + DESTINATION_AHEAD
ROBOT_HALF = (0.05, 0.07, 0.20)
"""Half extents (m) of the robot's block (depth, width, height)."""
FOOT_RADIUS = 0.02
ROBOT_MASS = 3.0
ROBOT_FORCE = 20.0
"""Force limit (N) of each walking actuator: enough for the light box, not the heavy one."""
WALK_SPEED = 0.3
"""Speed (m/s) of the walking set-point."""
CAMERA_HEIGHT = 0.45
"""Height of the robot's camera above the table top (h_r2t of eq. 3.11)."""
CAMERA_FOVY = 60.0
BOX_HALF = (0.075, 0.135, 0.11)
"""Half extents (m) of each box: 0.15 deep, 0.27 wide, 0.22 high."""
BOX_FRONT_X = START_X + ROBOT_HALF[0] + 0.02
"""The boxes' front faces start 2 cm in front of the robot."""
BOX_Y = 0.15
"""The boxes' centres are BOX_Y left and right of the table's centre line."""
BOX_MASS = {"movable": 0.4, "fixed": 40.0}
MARKER_HALF = (0.02, 0.04, 0.001)
"""Half extents (m) of an object's colour marker: 4 cm deep, 8 cm wide, flat on its top face."""
MARKER_RGBA = {"red": "0.85 0.05 0.05 1", "green": "0.10 0.72 0.10 1",
               "blue": "0.05 0.15 0.85 1"}
"""The marker colours of every task world (the perception's palette)."""
BOX_COLOUR = {"movable": "blue", "fixed": "red"}
TORSO_CONTACT = 'contype="2" conaffinity="2"'
BOX_CONTACT = 'contype="3" conaffinity="3"'
"""Collision bits: the torso meets boxes but never the table, so only the foot holds the robot
up and a foot past the edge drops it; boxes meet the table, the foot and the torso."""
RGBA = {"table": "0.76 0.72 0.66 1", "floor": "0.55 0.55 0.58 1", "wall": "0.45 0.47 0.50 1",
        "robot": "0.92 0.92 0.92 1", "box": "0.80 0.80 0.82 1", "line": "0.97 0.97 0.97 1"}


@dataclass(frozen=True)
class BoxState:
    """Ground truth of one box: centre, orientation, colour, whether it can move."""

    name: str
    pos: tuple[float, float, float]
    quat: tuple[float, float, float, float]
    colour: str
    movable: bool


@dataclass(frozen=True)
class NavigationState:
    """Ground truth of the navigation world at one instant."""

    robot: tuple[float, float, float]
    fallen: bool
    distance: float
    boxes: dict[str, BoxState]


def build_mjcf() -> str:
    """The navigation scene as MJCF text (boxes placed by ``NavigationWorld.reset``)."""
    (x0, x1), (y0, y1) = TABLE_X, TABLE_Y
    rx, ry, rz = ROBOT_HALF
    eye = (-0.04, 0.0, CAMERA_HEIGHT)
    parts = ['<mujoco model="navigation">',
             '<compiler angle="radian" autolimits="true"/>',
             '<option timestep="0.002" integrator="implicitfast" cone="elliptic"/>',
             LIGHTING,
             '<default><geom friction="0.5 0.005 0.0001" solref="0.004 1"/></default>',
             "<worldbody>",
             '<light name="top" pos="0.4 0 2.2" dir="0 0 -1" diffuse="0.45 0.45 0.45" '
             'castshadow="false"/>',
             box("floor", (0.4, 0, -0.005), (2, 2, 0.005), RGBA["floor"]),
             box("table", ((x0 + x1) / 2, (y0 + y1) / 2, TABLE_TOP / 2),
                 ((x1 - x0) / 2, (y1 - y0) / 2, TABLE_TOP / 2), RGBA["table"]),
             box("destination", (DESTINATION_X, 0, TABLE_TOP + 0.0005),
                 (0.005, (y1 - y0) / 2, 0.0005), RGBA["line"], collide=False),
             box("backdrop", (1.6, 0, 1.0), (0.01, 2.0, 1.0), RGBA["wall"], collide=False),
             f'<body name="robot" pos="{fmt(START_X, 0, TABLE_TOP)}">',
             '<joint name="walk_x" type="slide" axis="1 0 0" damping="10"/>',
             '<joint name="walk_y" type="slide" axis="0 1 0" damping="10"/>',
             '<joint name="fall_z" type="slide" axis="0 0 1" damping="2" '
             f'range="{-TABLE_TOP} 0.05"/>',
             f'<geom name="foot" type="sphere" pos="0 0 {FOOT_RADIUS}" size="{FOOT_RADIUS}" '
             f'friction="0.05 0.005 0.0001" mass="0.5" rgba="{RGBA["robot"]}"/>',
             box("torso", (0, 0, FOOT_RADIUS + 0.01 + rz), (rx, ry, rz), RGBA["robot"],
                 extra=f' mass="{ROBOT_MASS - 0.5}" friction="0.8 0.005 0.0001" {TORSO_CONTACT}'),
             f'<camera name="head" pos="{fmt(*eye)}" fovy="{CAMERA_FOVY}" '
             f'xyaxes="{look_at(eye, (0.20, 0.0, 0.0))}"/>',
             "</body>"]
    for name, colour in BOX_COLOUR.items():
        bx, by, bz = BOX_HALF
        mz = MARKER_HALF[2]
        parts += [f'<body name="box_{name}" pos="{fmt(BOX_FRONT_X + bx, 0, TABLE_TOP + bz)}">',
                  f'<freejoint name="box_{name}_free"/>',
                  box(f"box_{name}", (0, 0, 0), BOX_HALF, RGBA["box"],
                      extra=f' mass="{BOX_MASS[name]}" {BOX_CONTACT}'),
                  box(f"marker_{name}", (0, 0, bz + mz), MARKER_HALF, MARKER_RGBA[colour],
                      collide=False),
                  "</body>"]
    parts += ["</worldbody>", "<actuator>"]
    for axis in "xy":
        parts.append(f'<position name="walk_{axis}" joint="walk_{axis}" kp="3000" '
                     f'forcerange="{fmt(-ROBOT_FORCE, ROBOT_FORCE)}"/>')
    parts += ["</actuator>", "</mujoco>"]
    return "\n".join(parts) + "\n"


class NavigationWorld(RenderedWorld):
    """The robot, the movable and the fixed box on the table, and the destination line."""

    DIRECTIONS = {"left": (0.0, 1.0), "ahead": (1.0, 0.0), "right": (0.0, -1.0)}
    """Walking directions (x, y) in the world frame."""
    table_top, table_x, table_y = TABLE_TOP, TABLE_X, TABLE_Y

    def __init__(self, exchanged: bool = False, width: int = 320, height: int = 240):
        """Build the scene with the fixed box on the left (or, ``exchanged``, on the right)."""
        super().__init__(build_mjcf(), width, height)
        m = self.model
        self._robot = m.body("robot").id
        self._boxes = {name: m.body(f"box_{name}").id for name in BOX_COLOUR}
        self._is_box = np.zeros(m.nbody, dtype=bool)  # body id -> is it a box
        self._is_box[list(self._boxes.values())] = True
        self._walk = [m.joint("walk_x").qposadr[0], m.joint("walk_y").qposadr[0]]
        self._fall = m.joint("fall_z").qposadr[0]
        self.exchanged = exchanged
        self.reset(exchanged)

    def reset(self, exchanged: bool | None = None, lane: float = START_LANE) -> None:
        """Put the robot at the start in ``lane`` (one of ``LANES``) and the boxes in place
        (``exchanged`` swaps them)."""
        if lane not in LANES:
            raise ValueError(f"lane {lane!r} is not one of {LANES}")
        if exchanged is not None:
            self.exchanged = bool(exchanged)
        mujoco.mj_resetData(self.model, self.data)
        d = self.data
        d.qpos[self._walk[1]] = lane
        d.ctrl[:] = [0.0, lane]
        fixed_side = -1.0 if self.exchanged else 1.0  # left (+y) during the first trials
        for name, side in (("fixed", fixed_side), ("movable", -fixed_side)):
            joint = d.joint(f"box_{name}_free")
            joint.qpos[:3] = (BOX_FRONT_X + BOX_HALF[0], side * BOX_Y, TABLE_TOP + BOX_HALF[2])
            joint.qpos[3:] = (1, 0, 0, 0)
        mujoco.mj_forward(self.model, d)
        self.settle(300)

    # ---------------------------------------------------------------- the robot
    @property
    def robot_pos(self) -> np.ndarray:
        """The robot's centre on the ground plane of its foot (x, y, z of the foot's bottom)."""
        return self.data.xpos[self._robot].copy()

    @property
    def fallen(self) -> bool:
        """True once the robot has dropped off the table."""
        return bool(self.data.qpos[self._fall] < -0.05)

    def distance_to_destination(self) -> float:
        """How far (m) the robot still is from the destination line (0 once across it)."""
        return max(0.0, DESTINATION_X - float(self.robot_pos[0]))

    def walk(self, direction: str) -> bool:
        """Walk ``D_WALK`` m left, ahead or right; stop on touching a box. True if it got there."""
        if direction not in self.DIRECTIONS:
            raise ValueError(f"unknown direction {direction!r}; use left, ahead or right")
        dx, dy = self.DIRECTIONS[direction]
        return self._move(np.array([dx, dy]) * D_WALK, guarded=True)

    def push(self) -> bool:
        """Walk ``D_WALK`` m ahead leaning into whatever is in front. True if it got there."""
        return self._move(np.array([D_WALK, 0.0]), guarded=False)

    def _move(self, delta: np.ndarray, guarded: bool) -> bool:
        """Ramp the walking set-point by ``delta``; hold, settle and report arrival."""
        d = self.data
        start = d.ctrl[:2].copy()
        target = start + delta
        n = max(1, int(np.ceil(np.linalg.norm(delta) / (WALK_SPEED * self.model.opt.timestep))))
        heading = delta / np.linalg.norm(delta)
        for i in range(1, n + 1):
            d.ctrl[:2] = start + delta * (i / n)
            self.step()
            if guarded and self.blocked(heading):
                d.ctrl[:2] = d.qpos[self._walk]  # stop where the robot is
                break
        for _ in range(300):
            self.step()
            if np.linalg.norm(d.qpos[self._walk] - d.ctrl[:2]) < 2e-3:
                break
        arrived = bool(np.linalg.norm(d.qpos[self._walk] - target) < 5e-3)
        d.ctrl[:2] = d.qpos[self._walk]  # stop pressing against whatever held the robot up
        self.settle()
        return arrived

    def blocked(self, heading: np.ndarray) -> bool:
        """True if a box touches the robot on its side facing ``heading`` (x, y unit vector)."""
        n = self.data.ncon
        if n == 0:
            return False
        contacts = self.data.contact
        body1 = self.model.geom_bodyid[contacts.geom1[:n]]
        body2 = self.model.geom_bodyid[contacts.geom2[:n]]
        along = contacts.frame[:n, :2] @ heading  # contact normals point from geom1 to geom2
        ahead = (((body1 == self._robot) & self._is_box[body2] & (along > 0.5))
                 | ((body2 == self._robot) & self._is_box[body1] & (along < -0.5)))
        return bool(ahead.any())

    # ---------------------------------------------------------------- truth
    @staticmethod
    def markers() -> dict[str, str]:
        """Each object's name and marker colour (its marker geom is ``marker_<name>``)."""
        return dict(BOX_COLOUR)

    def box_state(self, name: str) -> BoxState:
        """Ground truth of the ``movable`` or the ``fixed`` box."""
        body = self._boxes[name]
        return BoxState(name, tuple(float(v) for v in self.data.xpos[body]),
                        tuple(float(v) for v in self.data.xquat[body]), BOX_COLOUR[name],
                        name == "movable")

    def state(self) -> NavigationState:
        """Ground truth now: robot, whether it fell, distance to go, both boxes."""
        return NavigationState(tuple(float(v) for v in self.robot_pos), self.fallen,
                               self.distance_to_destination(),
                               {name: self.box_state(name) for name in BOX_COLOUR})


if __name__ == "__main__":
    print(build_mjcf(), end="")
