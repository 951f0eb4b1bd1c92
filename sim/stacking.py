"""The stacking world of thesis Fig. 3.4: push objects off the table into a stack as high as it.

World frame: the robot stands near the table's far edge facing +x, the edge at x = ``EDGE_X``.
Beside the table, past the edge, is a well with a lift: its platform starts level with the
table top, an object pushed off the table slides onto it (or onto the stack on it), and the
lift then sinks until the stack's top is level with the table again, like a plate dispenser.
(Objects pushed over a bare edge tip and land on their sides or jam, which makes no stack.)
The stack is as high as the table once its height reaches the table's. The table is as high
as the high box (36 cm); the low foam is a third of that (12 cm, thesis sizes). Both have the
same 20 x 20 cm footprint and a colour marker in the middle of the top face: blue on the box,
green on the foams.

The robot (a stand-in for the NAO) does not walk here: a torso on a vertical slide stands or
squats, and a pusher bar on a horizontal slide in front of it pushes ``PUSH_STROKE`` m ahead.
Standing, the bar sweeps 14-20 cm above the table, over the low foam; squatting lowers it to
3-9 cm. So the effect of a push depends on the pose (actions 100 and 101 of Table 3.1).
Choosing an object (110, 111) stands for asking the human operator (§3.5.4): the next unused
object of that kind is put in front of the robot (the one standing there is taken back).
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from sim.base import RenderedWorld
from sim.mjcf import LIGHTING, box, fmt, look_at
from sim.navigation import MARKER_HALF, MARKER_RGBA

TABLE_TOP = 0.36
"""Height of the table (m): as high as the high box, so that box alone is a full stack."""
EDGE_X = 0.30
"""x (m) of the table edge the objects are pushed over."""
TABLE_X = (-0.45, EDGE_X)
TABLE_Y = (-0.30, 0.30)
OBJECT_HALF = {"box": (0.10, 0.10, 0.18), "foam": (0.10, 0.10, 0.06)}
"""Half extents (m): the high box is 36 cm high, the low foam 12 cm (Fig. 3.4)."""
OBJECT_MASS = {"box": 0.5, "foam": 0.05}
OBJECT_COLOUR = {"box": "blue", "foam": "green"}
OBJECTS = ("box", "foam1", "foam2", "foam3")
"""One high box and three foams: three foams also make a full stack."""
KINDS = ("box", "foam")
"""What the operator can be asked for: object 1 is the high box, object 2 a low foam."""
ROBOT_X = -0.10
"""x (m) of the robot's centre."""
TORSO_HALF = (0.05, 0.08, 0.16)
LEG_HEIGHT = 0.12
"""The torso sits on legs this high when standing; squatting lowers it by ``SQUAT_DROP``."""
SQUAT_DROP = 0.11
BAR_HALF = (0.015, 0.08, 0.03)
BAR_Z = 0.17
"""Height (m) of the pusher bar's centre above the table when standing (bar spans 14-20 cm)."""
PUSH_STROKE = 0.34
"""How far (m) the bar moves ahead in a push: far enough to tip an object over the edge."""
PUSH_FORCE = 30.0
PUSH_SPEED = 0.4
"""Speed (m/s) of the pusher's set-point on the way out."""
RETURN_SPEED = 1.0
"""Speed (m/s) of the pusher coming back and of the torso squatting or standing up."""
PLACE_X = ROBOT_X + TORSO_HALF[0] + 0.035
"""x (m) of the near face of an object the operator puts in front of the robot."""
CAMERA_HEIGHT = 0.50
"""Height of the camera (a head above the torso) over the table top when standing (h_r2t of
eq. 3.11)."""
CAMERA_FOVY = 60.0
WELL_INNER = (0.24, 0.24)
"""Inside of the well (x, y, m): the platform and room for an object pushed onto it."""
WALL = 0.01
LIFT_SPEED = 0.2
"""Speed (m/s) at which the lift sinks."""
STACK_TOLERANCE = 0.015
"""A stack counts as high as the table within this margin (m)."""
POOL = (-0.2, 1.2)
"""(x, y) where unused objects wait, out of the robot's view."""
OBJECT_CONTACT = 'contype="3" conaffinity="3"'
RGBA = {"table": "0.76 0.72 0.66 1", "floor": "0.55 0.55 0.58 1", "wall": "0.45 0.47 0.50 1",
        "robot": "0.92 0.92 0.92 1", "box": "0.80 0.80 0.82 1", "foam": "0.93 0.90 0.80 1",
        "well": "0.35 0.35 0.38 1", "lift": "0.25 0.25 0.28 1"}


@dataclass(frozen=True)
class StackingState:
    """Ground truth of the stacking world at one instant."""

    pose: str
    in_front: str | None
    stacked_objects: tuple[str, ...]
    stack_height: float
    stacked: bool


def kind_of(name: str) -> str:
    """``box`` or ``foam`` for an object name."""
    return "box" if name == "box" else "foam"


def _pool_pos(index: int, name: str) -> tuple[float, float, float]:
    """Where object number ``index`` waits when unused (on the floor, side by side)."""
    return (POOL[0] + 0.3 * index, POOL[1], OBJECT_HALF[kind_of(name)][2])


def build_mjcf() -> str:
    """The stacking scene as MJCF text."""
    (x0, x1), (y0, y1) = TABLE_X, TABLE_Y
    tx, ty, tz = TORSO_HALF
    well_x, well_y = WELL_INNER
    eye = (0.04, 0.0, CAMERA_HEIGHT - LEG_HEIGHT)
    parts = ['<mujoco model="stacking">',
             '<compiler angle="radian" autolimits="true"/>',
             '<option timestep="0.002" integrator="implicitfast" cone="elliptic"/>',
             LIGHTING,
             '<default><geom friction="0.3 0.005 0.0001" solref="0.004 1"/></default>',
             "<worldbody>",
             '<light name="top" pos="0 0 2.2" dir="0 0 -1" diffuse="0.45 0.45 0.45" '
             'castshadow="false"/>',
             box("floor", (0, 0, -0.005), (2, 2, 0.005), RGBA["floor"]),
             box("table", ((x0 + x1) / 2, (y0 + y1) / 2, TABLE_TOP / 2),
                 ((x1 - x0) / 2, (y1 - y0) / 2, TABLE_TOP / 2), RGBA["table"]),
             box("backdrop", (1.6, 0, 1.0), (0.01, 2.0, 1.0), RGBA["wall"], collide=False),
             box("legs", (ROBOT_X, 0, TABLE_TOP + LEG_HEIGHT / 2), (0.03, 0.05, LEG_HEIGHT / 2),
                 RGBA["robot"], collide=False)]
    # The well: its near wall is the table's side; the far wall rises 10 cm over the table
    # as a backstop; all walls are slippery so the stack sinks freely with the lift.
    wall = f' friction="0.02 0.005 0.0001" {OBJECT_CONTACT}'
    high = (TABLE_TOP + 0.10) / 2
    parts += [box("well_far", (EDGE_X + well_x + WALL / 2, 0, high),
                  (WALL / 2, well_y / 2 + WALL, high), RGBA["well"], extra=wall)]
    for name, sign in (("well_left", 1), ("well_right", -1)):
        parts.append(box(name, (EDGE_X + well_x / 2, sign * (well_y + WALL) / 2, high),
                         (well_x / 2, WALL / 2, high), RGBA["well"], extra=wall))
    parts += [f'<body name="lift" pos="{fmt(EDGE_X + well_x / 2, 0, TABLE_TOP)}">',
              f'<joint name="lift" type="slide" axis="0 0 1" range="{-TABLE_TOP} 0" '
              'damping="200"/>',
              box("platform", (0, 0, -0.005), (well_x / 2 - 0.002, well_y / 2 - 0.002, 0.005),
                  RGBA["lift"], extra=f' mass="1" {OBJECT_CONTACT}'),
              "</body>"]
    parts += [f'<body name="torso" pos="{fmt(ROBOT_X, 0, TABLE_TOP + LEG_HEIGHT)}">',
              f'<joint name="squat" type="slide" axis="0 0 1" range="{-SQUAT_DROP} 0" '
              'damping="50"/>',
              box("torso", (0, 0, tz), (tx, ty, tz), RGBA["robot"], collide=False,
                  extra=' mass="2"'),
              f'<camera name="head" pos="{fmt(*eye)}" fovy="{CAMERA_FOVY}" '
              f'xyaxes="{look_at(eye, (0.25, 0.0, -LEG_HEIGHT))}"/>',
              f'<body name="pusher" pos="{fmt(tx + BAR_HALF[0], 0, BAR_Z - LEG_HEIGHT)}">',
              f'<joint name="push" type="slide" axis="1 0 0" range="0 {PUSH_STROKE}" '
              'damping="20"/>',
              box("pusher", (0, 0, 0), BAR_HALF, RGBA["robot"],
                  extra=f' mass="0.3" friction="0.6 0.005 0.0001" {OBJECT_CONTACT}'),
              "</body>", "</body>"]
    for index, name in enumerate(OBJECTS):
        kind = kind_of(name)
        hx, hy, hz = OBJECT_HALF[kind]
        mz = MARKER_HALF[2]
        parts += [f'<body name="{name}" pos="{fmt(*_pool_pos(index, name))}">',
                  f'<freejoint name="{name}_free"/>',
                  box(name, (0, 0, 0), (hx, hy, hz), RGBA[kind],
                      extra=f' mass="{OBJECT_MASS[kind]}" {OBJECT_CONTACT}'),
                  box(f"marker_{name}", (0, 0, hz + mz), MARKER_HALF,
                      MARKER_RGBA[OBJECT_COLOUR[kind]], collide=False),
                  "</body>"]
    parts += ["</worldbody>", "<actuator>",
              '<position name="squat" joint="squat" kp="4000" forcerange="-200 200"/>',
              f'<position name="push" joint="push" kp="3000" '
              f'forcerange="{fmt(-PUSH_FORCE, PUSH_FORCE)}"/>',
              '<position name="lift" joint="lift" kp="20000" forcerange="-500 500"/>',
              "</actuator>", "</mujoco>"]
    return "\n".join(parts) + "\n"


class StackingWorld(RenderedWorld):
    """The robot at the table edge, the box and the foams, and the lift beside the table."""

    POSES = ("stand", "squat")
    table_top, table_x, table_y = TABLE_TOP, TABLE_X, TABLE_Y

    def __init__(self, width: int = 320, height: int = 240):
        """Build the scene, everything in its initial place."""
        super().__init__(build_mjcf(), width, height)
        self._squat = self.model.joint("squat").qposadr[0]
        self._lift = self.model.joint("lift").qposadr[0]
        self._bodies = {name: self.model.body(name).id for name in OBJECTS}
        self.reset()

    def reset(self) -> None:
        """Stand up, raise the empty lift and give every object back to the operator."""
        mujoco.mj_resetData(self.model, self.data)
        for index, name in enumerate(OBJECTS):
            self._place(name, _pool_pos(index, name))
        self.in_front: str | None = None
        mujoco.mj_forward(self.model, self.data)
        self.settle(200)

    def _place(self, name: str, pos: tuple[float, float, float]) -> None:
        """Put object ``name`` upright at ``pos`` (its centre), at rest."""
        joint = self.data.joint(f"{name}_free")
        joint.qpos[:] = (*pos, 1, 0, 0, 0)
        joint.qvel[:] = 0.0

    # ---------------------------------------------------------------- actions
    def choose(self, kind: str) -> bool:
        """Have the operator put an unused ``box`` or ``foam`` in front; False if none is left."""
        if kind not in KINDS:
            raise ValueError(f"unknown object kind {kind!r}; use box or foam")
        spare = [n for n in OBJECTS if kind_of(n) == kind and self._in_pool(n)]
        if self.in_front is not None and self._on_table(self.in_front):
            index = OBJECTS.index(self.in_front)
            self._place(self.in_front, _pool_pos(index, self.in_front))
            if kind_of(self.in_front) == kind:
                spare.insert(0, self.in_front)
        self.in_front = None
        if not spare:
            mujoco.mj_forward(self.model, self.data)
            return False
        name = spare[0]
        hz = OBJECT_HALF[kind][2]
        self._place(name, (PLACE_X + OBJECT_HALF[kind][0], 0.0, TABLE_TOP + hz))
        self.in_front = name
        mujoco.mj_forward(self.model, self.data)
        self.settle(300)
        return True

    def push(self, pose: str) -> None:
        """Take ``pose`` (stand or squat), push the bar ahead and back, then stand up; the
        lift then sinks until the stack's top is level with the table again."""
        if pose not in self.POSES:
            raise ValueError(f"unknown pose {pose!r}; use stand or squat")
        self._ramp(0, -SQUAT_DROP if pose == "squat" else 0.0, RETURN_SPEED)
        self._ramp(1, PUSH_STROKE)
        self._ramp(1, 0.0, RETURN_SPEED)
        self._ramp(0, 0.0, RETURN_SPEED)
        self.settle(1000)
        if self.in_front is not None and not self._on_table(self.in_front):
            self.in_front = None
        excess = self.stack_top() - TABLE_TOP
        if excess > STACK_TOLERANCE:
            self._ramp(2, max(-TABLE_TOP, float(self.data.ctrl[2]) - excess), LIFT_SPEED)
            self.settle(1000)

    def _ramp(self, actuator: int, target: float, speed: float = PUSH_SPEED) -> None:
        """Move one actuator's set-point to ``target`` at ``speed``, then let it arrive."""
        start = float(self.data.ctrl[actuator])
        n = max(1, int(abs(target - start) / (speed * self.model.opt.timestep)))
        for i in range(1, n + 1):
            self.data.ctrl[actuator] = start + (target - start) * i / n
            self.step()
        self.step(50)

    # ---------------------------------------------------------------- truth
    @staticmethod
    def markers() -> dict[str, str]:
        """Each object's name and marker colour (its marker geom is ``marker_<name>``)."""
        return {name: OBJECT_COLOUR[kind_of(name)] for name in OBJECTS}

    @property
    def robot_pos(self) -> np.ndarray:
        """The robot's centre on the table (x, y, z of its feet)."""
        return np.array([ROBOT_X, 0.0, TABLE_TOP])

    def _in_pool(self, name: str) -> bool:
        return bool(self.data.xpos[self._bodies[name]][1] > POOL[1] - 0.3)

    def _on_table(self, name: str) -> bool:
        x, _, z = self.data.xpos[self._bodies[name]]
        return bool(TABLE_X[0] < x < EDGE_X and z > TABLE_TOP)

    def _in_well(self, name: str) -> bool:
        x, y, _ = self.data.xpos[self._bodies[name]]
        return bool(EDGE_X < x < EDGE_X + WELL_INNER[0] and abs(y) < WELL_INNER[1] / 2)

    def top_of(self, name: str) -> float:
        """Highest point (m above the floor) of object ``name`` as it lies now."""
        body = self._bodies[name]
        half = np.array(OBJECT_HALF[kind_of(name)])
        rot = self.data.xmat[body].reshape(3, 3)
        return float(self.data.xpos[body][2] + np.abs(rot[2]) @ half)

    def platform_top(self) -> float:
        """Height (m above the floor) of the lift's platform."""
        return float(TABLE_TOP + self.data.qpos[self._lift])

    def stack_top(self) -> float:
        """Height (m above the floor) of the top of the stack (the platform when empty)."""
        return max((self.top_of(n) for n in OBJECTS if self._in_well(n)),
                   default=self.platform_top())

    def stack_height(self) -> float:
        """How high (m) the stack on the lift is."""
        return self.stack_top() - self.platform_top()

    @property
    def pose(self) -> str:
        """``squat`` while the torso is lowered, else ``stand``."""
        return "squat" if self.data.qpos[self._squat] < -SQUAT_DROP / 2 else "stand"

    def state(self) -> StackingState:
        """Ground truth now: pose, the object in front, what is on the lift and how high."""
        height = self.stack_height()
        return StackingState(self.pose, self.in_front,
                             tuple(n for n in OBJECTS if self._in_well(n)), height,
                             height >= TABLE_TOP - STACK_TOLERANCE)


if __name__ == "__main__":
    print(build_mjcf(), end="")
