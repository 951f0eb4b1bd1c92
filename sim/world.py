"""The garbage-can world: one MuJoCo scene of sim/scene.py plus the calls a robot body offers.

``GarbageWorld`` is a ``RenderedWorld`` (sim/base.py: the model and data, settling, headless
rendering, the camera model) whose model is rebuilt when the can changes. It moves the
Cartesian arm (position-controlled, force-limited slide actuators; every move is a
straight-line ramp of the set-point followed by settling), grasps and drops the ball (a weld
equality switched on and off) and reports ground truth (``state()``). Two jobs are mixins of
their own: holding a part with the hand (sim/hold.py) and recording mp4 videos of the head
camera (sim/recording.py); ``step`` runs their hooks around every physics step.

The opening is the straight-line gap (m) between the rim's front edge and the lid's front edge,
i.e. the width of the dark gap the thesis measures in the image (eq. 5.14). Seen from the head
camera, the dark region (interior and lid underside, both near black) spans exactly that gap;
its bounding-box height in pixels times (body marker width in m / its width in pixels) gives
the opening within about 5 mm over 0.02..0.15 m on every can (the body marker's horizontal
width is not foreshortened by the camera's pitch and lies at the rim's depth).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import mujoco
import numpy as np

from sim.base import CameraModel, RenderedWorld
from sim.hold import HandHold
from sim.recording import Recording
from sim.scene import (
    ARM_KP,
    ARM_RANGE,
    BALL_RADIUS,
    CANS,
    GRIP_OFFSET,
    HOME,
    MARKER_SIZE,
    TABLE_TOP,
    WALL,
    CanSpec,
    build_mjcf,
)

__all__ = ["CANS", "MARKER_SIZE", "CameraModel", "CanSpec", "GarbageWorld", "PartState",
           "WorldState"]

ARM_SPEED = 0.4
"""Speed (m/s) of the arm's set-point along a straight-line move."""
ARRIVE_TOL = 1.5e-3
"""Distance (m) from the set-point at which the hand counts as arrived."""
CAN_PARTS = ("can_body", "lid", "lid_tab", "handle", "pedal")
"""The bodies a can may have (a sliding lid's tab, a handle, a pedal only on some cans)."""


@dataclass(frozen=True)
class PartState:
    """Ground-truth pose of one part's colour marker: centre, orientation, full extents (m)."""

    pos: tuple[float, float, float]
    quat: tuple[float, float, float, float]
    size: tuple[float, float, float]


@dataclass(frozen=True)
class WorldState:
    """Ground truth of the world at one instant."""

    opening: float
    lid_angle: float  # the lid joint's position: an angle (rad), or metres for a sliding lid
    parts: dict[str, PartState]
    ball_pos: tuple[float, float, float]
    holding_ball: bool
    ball_in_can: bool
    effector_pos: tuple[float, float, float]


class GarbageWorld(HandHold, Recording, RenderedWorld):
    """One can on a table, a Cartesian arm with a grasping hand, a ball and a head camera."""

    default_camera = "head"
    settle_steps = 2000

    def __init__(self, can: str | CanSpec = "o1", seed: int = 0, width: int = 320,
                 height: int = 240):
        """Build the scene of ``can`` (a thesis can's name or any CanSpec), reset under seed."""
        spec = _spec_of(can)
        super().__init__(build_mjcf(spec), width, height)
        self._spec = spec
        self._seed = seed
        self.reset(seed=seed)

    # ----------------------------------------------------------------- set-up
    def reset(self, can: str | CanSpec | None = None, seed: int | None = None) -> None:
        """Restore the initial scene (closed lid, ball on the table, hand home)."""
        if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int)):
            raise ValueError(f"seed must be an integer, got {seed!r}")
        spec = self._spec if can is None else _spec_of(can)
        if spec != self._spec:
            self.load(build_mjcf(spec))
            self._spec = spec
        if seed is not None:
            self._seed = seed
        m, d = self.model, self.data
        mujoco.mj_resetData(m, d)
        rng = np.random.default_rng(self._seed)
        ball = d.joint("ball_free").qpos
        ball[:2] += rng.uniform(-0.01, 0.01, size=2)
        self._grip_id = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_EQUALITY, "grip")
        d.eq_active[self._grip_id] = 0
        self._reset_holds()
        self.arm_stiffness = ARM_KP
        self.set_ball_collisions(True)
        self._hand_dadr = [m.jnt_dofadr[m.joint(f"arm_{a}").id] for a in "xyz"]
        self._ball_body = m.body("ball").id
        self._hand_body = m.body("hand").id
        self._can_bodies = np.array([m.body(n).id for n in CAN_PARTS if _has_body(m, n)])
        self.steps = 0
        mujoco.mj_forward(m, d)
        self._restart_recording_clock()
        self.settle(500)

    @property
    def can(self) -> str:
        """Name of the current can (o1..o5, or a can file's name)."""
        return self.spec.name

    @property
    def spec(self) -> CanSpec:
        """Geometry and mechanism of the current can."""
        assert self._spec is not None
        return self._spec

    @property
    def parts(self) -> tuple[str, ...]:
        """Parts of the current can."""
        return self.spec.parts

    @property
    def seed(self) -> int:
        """Seed of the last reset."""
        return self._seed

    # ---------------------------------------------------------------- physics
    def step(self, n: int = 1) -> None:
        """Advance the physics ``n`` steps, one at a time: a sliding hold's anchor follows the
        hand and the recorder (if one is running) is fed between steps."""
        for _ in range(n):
            self._follow_hand()
            mujoco.mj_step(self.model, self.data)
            self.steps += 1
            self._record_frame()

    # -------------------------------------------------------------------- arm
    @property
    def effector_pos(self) -> np.ndarray:
        """Current hand centre in the world (m)."""
        return self.data.xpos[self._hand_body].copy()

    @property
    def setpoint(self) -> np.ndarray:
        """Where the arm's position controllers currently aim the hand (world frame)."""
        return np.asarray(HOME) + self.data.ctrl[:3]

    def move_arm(self, dx: float, dy: float, dz: float) -> bool:
        """Move the hand by (dx, dy, dz) m from where it is; True if it got there."""
        return self.move_arm_to(self.effector_pos + np.array([dx, dy, dz], dtype=float))

    def move_arm_to(self, target_xyz: Sequence[float] | np.ndarray,
                    stop_if: Callable[[], bool] | None = None) -> bool:
        """Move the hand in a straight line to ``target_xyz`` (clipped to the reachable box).

        The set-point ramps at ``ARM_SPEED``; the hand follows with force-limited actuators, so
        an obstacle stops it. ``stop_if`` (checked every step) ends the move early, freezing
        the set-point where the hand is. Returns True if the hand reached the target.
        """
        target = np.asarray(target_xyz, dtype=float)
        if target.shape != (3,) or not np.all(np.isfinite(target)):
            raise ValueError(f"arm target must be three finite numbers, got {target_xyz!r}")
        lo = np.array([b[0] for b in ARM_RANGE])
        hi = np.array([b[1] for b in ARM_RANGE])
        target = np.clip(target, lo, hi)
        start = self.setpoint
        step_len = ARM_SPEED * self.model.opt.timestep
        n = max(1, math.ceil(np.linalg.norm(target - start) / step_len))
        # the whole ramp at once, element for element the sum start + (target - start)·i/n
        home = np.asarray(HOME)
        ramp = start + (target - start) * (np.arange(1, n + 1) / n)[:, None] - home
        for setpoint in ramp:
            self.data.ctrl[:3] = setpoint
            self.step()
            if stop_if is not None and stop_if():
                self.data.ctrl[:3] = self.effector_pos - home
                self.settle(300)
                return False
        # up to 400 steps of waiting, each checked: the hand's position is read as a view that
        # every step updates, and its distance is np.linalg.norm's own sqrt(x . x), spelled out
        hand, velocity = self.data.xpos[self._hand_body], self.data.qvel
        for _ in range(400):
            self.step()
            gap = hand - target
            if (math.sqrt(gap.dot(gap)) < ARRIVE_TOL
                    and float(np.abs(velocity[self._hand_dadr]).max()) < 1e-2):
                break
        return bool(np.linalg.norm(self.effector_pos - target) < 3 * ARRIVE_TOL)

    @property
    def arm_stiffness(self) -> float:
        """Stiffness (N/m) of the arm's position control (``ARM_KP`` after every reset)."""
        return float(self.model.actuator_gainprm[0, 0])

    @arm_stiffness.setter
    def arm_stiffness(self, kp: float) -> None:
        if not (isinstance(kp, int | float) and math.isfinite(kp) and kp > 0):
            raise ValueError(f"arm stiffness must be a positive number of N/m, got {kp!r}")
        for axis in "xyz":
            actuator = self.model.actuator(f"act_{axis}").id
            self.model.actuator_gainprm[actuator, 0] = kp
            self.model.actuator_biasprm[actuator, 1] = -kp

    def home(self) -> bool:
        """Move the hand back to its resting position beside the can."""
        return self.move_arm_to(HOME)

    def relax(self) -> None:
        """Aim the arm's controllers at where the hand is, so it pushes on nothing, and settle."""
        self.data.ctrl[:3] = self.effector_pos - np.asarray(HOME)
        self.settle(300)

    # ------------------------------------------------------------------- ball
    @property
    def grip_point(self) -> np.ndarray:
        """Where a grasped ball's centre is held (just in front of the hand)."""
        return self.effector_pos + np.array([GRIP_OFFSET, 0.0, 0.0])

    def grasp(self) -> bool:
        """Close the hand on the ball if it is within reach of the grip point; True if held."""
        ball = self.data.xpos[self._ball_body]
        if np.linalg.norm(ball - self.grip_point) > 0.015:
            return bool(self.data.eq_active[self._grip_id])
        self.data.eq_active[self._grip_id] = 1
        self.set_ball_collisions(False)
        self.step(100)
        return True

    def drop(self) -> None:
        """Open the hand: the ball (if held) falls; then let the world settle."""
        self.data.eq_active[self._grip_id] = 0
        self.set_ball_collisions(True)
        self.settle(1500)

    def set_ball_collisions(self, on: bool) -> None:
        """Let the ball collide (free or presented) or not (tucked in the closed hand).

        A held ball is tucked away so that carrying it does not change what the arm skills
        do to the can; ``drop_ball`` presents it (collisions on) before guiding it in.
        """
        geom = self.model.geom("ball").id
        self.model.geom_contype[geom] = int(on)
        self.model.geom_conaffinity[geom] = int(on)

    def ball_touches_can(self) -> bool:
        """True if the ball currently touches the can: its body, lid (or a sliding lid's tab),
        handle or pedal."""
        # checked after every physics step of a drop, so the contacts are read as arrays:
        # row k is the two bodies of contact k; a hit is the ball on one side, a can part on
        # the other (the columns swapped lines each body up with its partner)
        bodies = self.model.geom_bodyid[self.data.contact.geom[: self.data.ncon]]
        touching = (bodies == self._ball_body) & np.isin(bodies[:, ::-1], self._can_bodies)
        return bool(touching.any())

    # ------------------------------------------------------------------ truth
    def opening(self) -> float:
        """Gap (m) between the rim's front edge and the lid's front edge."""
        gap = self.data.site("lid_front").xpos - self.data.site("rim_front").xpos
        return float(np.linalg.norm(gap))

    def free_rim_y(self) -> float:
        """Where across the can (world y, m) the rim's front edge is most open: the middle of
        the stretch a sideways-moved lid has uncovered, else the middle of the can (a hinged
        lid lifts off the whole edge)."""
        shift = float(self.data.site("lid_front").xpos[1] - self.data.site("rim_front").xpos[1])
        inner = self.spec.width / 2 - WALL
        uncovered = abs(shift) - WALL  # the lid's edge moved this far past the inner wall
        if uncovered <= 0.0:
            return 0.0
        return -math.copysign(inner - uncovered / 2, shift)

    def set_opening(self, width: float) -> None:
        """Put the lid (and a geared handle) where the opening is ``width`` m, at rest, and
        every part that gave a little (a handle's play, a sliding can) back in place."""
        m, d = self.model, self.data
        hinge = d.joint(self.spec.lid_joint)
        geared = self.spec.geared_joint
        slide = d.joint(geared) if geared is not None else None
        gear = self.spec.gear
        # the lid opens as far as its own joint or the geared joint's range allows
        lid_range = float(m.jnt_range[m.joint(self.spec.lid_joint).id][1])
        if geared is not None:
            lid_range = min(lid_range, gear * float(m.jnt_range[m.joint(geared).id][1]))

        def place(angle: float) -> float:
            hinge.qpos[0] = angle
            if slide is not None:
                slide.qpos[0] = angle / gear
            mujoco.mj_kinematics(m, d)
            return self.opening()

        top = place(lid_range)
        if not 0.0 <= width <= top:
            place(0.0)
            raise ValueError(f"opening {width} m outside 0..{top:.3f} m for can {self.can}")
        lo, hi = 0.0, lid_range
        for _ in range(50):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if place(mid) < width else (lo, mid)
        place((lo + hi) / 2)
        hinge.qvel[:] = 0.0
        if slide is not None:
            slide.qvel[:] = 0.0
        for name in self.spec.give_joints:  # parts that gave a little go back in place
            joint = d.joint(name)
            joint.qpos[:] = 0.0
            joint.qvel[:] = 0.0
        mujoco.mj_forward(m, d)

    def gap_corners(self) -> np.ndarray:
        """World corners (4, 3) of the dark gap the head camera sees into (eq. 4.19).

        The gap runs from the inner front edge of the rim (behind the front wall) to the lid's
        front edge, between the inner side walls; projected through the camera model, its
        bounding box matches the camera's dark region within 0.002 + 5 % of the image share.
        """
        half = self.spec.width / 2 - WALL
        rim = self.data.site("rim_front").xpos + np.array([WALL, 0.0, 0.0])
        lid = self.data.site("lid_front").xpos
        return np.array([rim + [0, -half, 0], rim + [0, half, 0],
                         lid + [0, half, 0], lid + [0, -half, 0]])

    def state(self) -> WorldState:
        """Ground truth now: opening, part markers, ball and hand."""
        m, d = self.model, self.data
        parts = {}
        for part in self.parts:
            g = m.geom(f"marker_{part}").id
            quat = np.zeros(4)
            mujoco.mju_mat2Quat(quat, d.geom_xmat[g])
            parts[part] = PartState(_float_tuple(d.geom_xpos[g]), _float_tuple(quat),
                                    _float_tuple(2 * m.geom_size[g]))
        ball = d.xpos[self._ball_body]
        return WorldState(
            opening=self.opening(),
            lid_angle=float(d.joint(self.spec.lid_joint).qpos[0]),
            parts=parts,
            ball_pos=_float_tuple(ball),
            holding_ball=bool(d.eq_active[self._grip_id]),
            ball_in_can=self._inside_can(ball),
            effector_pos=_float_tuple(self.effector_pos),
        )

    def _inside_can(self, p: np.ndarray) -> bool:
        """True if point ``p`` lies inside the can's walls, below the rim."""
        c = self.spec
        return bool(WALL < p[0] < c.depth - WALL and abs(p[1]) < c.width / 2 - WALL
                    and TABLE_TOP < p[2] < c.rim - BALL_RADIUS / 2)


def _spec_of(can: str | CanSpec) -> CanSpec:
    """The CanSpec of a thesis can's name, or ``can`` itself."""
    if isinstance(can, CanSpec):
        return can
    if can not in CANS:
        raise ValueError(f"unknown can {can!r}; expected one of {', '.join(CANS)}")
    return CANS[can]


def _has_body(model: mujoco.MjModel, name: str) -> bool:
    """True if the model has a body called ``name``."""
    return mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, name) >= 0


def _float_tuple(a: np.ndarray) -> tuple[float, ...]:
    """Plain-float tuple of a numpy vector (immutable, comparable, printable)."""
    return tuple(float(x) for x in a)
