"""Motor skills of the garbage-can robot: parameterised arm actions, grasp and drop (thesis §5.3.2).

Every arm skill ``a(θ)`` approaches the vicinity of the chosen part, moves the hand by θ metres
in the action type's direction, withdraws along the same line, returns home, lets the world
settle and reports the effect on the part (displacement of its marker, eq. 5.15) and on the
object (change of the opening, eq. 5.3), both from ground truth.

Approach points: a flat part (body, lid) is approached on its face, so an action starts just
in front of the face's marker (only pushing meets resistance there), except pressing a lid
down, which starts just above the lid's top near its front edge (this closes an open lid). A
handle (like
a pedal, or the tab on a sliding lid's front edge) is a bar standing off the can, so the hand
starts on the side of the bar opposite to the motion: in front of it to push, in the gap
behind it to pull, below it to lift, above it to press down, beside it to sweep; the hand
reaches the gap from below the bar.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from sim.scene import ARM_RANGE, BALL_RADIUS, GRIP_OFFSET, HAND_RADIUS, WALL
from sim.world import GarbageWorld

__all__ = ["ACTION_DIRECTIONS", "ACTION_TYPES", "THETA_BOUNDS", "DropResult", "SkillError",
           "SkillResult", "ball_within_reach", "check_skill", "drop_ball", "grasp_ball",
           "perform_skill"]

ACTION_TYPES: tuple[str, ...] = (
    "extend_arm", "contract_arm", "sweep_left", "sweep_right", "lift_up", "sweep_down",
)
"""Thesis §5.6.1 / §6.4.1 action types: push forward, pull back, sweep left/right, lift, down."""
ACTION_DIRECTIONS: dict[str, tuple[float, float, float]] = {
    "extend_arm": (1.0, 0.0, 0.0),
    "contract_arm": (-1.0, 0.0, 0.0),
    "sweep_left": (0.0, 1.0, 0.0),
    "sweep_right": (0.0, -1.0, 0.0),
    "lift_up": (0.0, 0.0, 1.0),
    "sweep_down": (0.0, 0.0, -1.0),
}
"""Unit direction of each action type in the world frame (robot faces +x, left is +y)."""
THETA_BOUNDS: dict[str, tuple[float, float]] = {a: (0.0, 0.1) for a in ACTION_TYPES}
"""Allowed θ per action type: lo < θ <= hi metres (thesis: 0 < θ <= θ0 = 0.1 m)."""

MARGIN = 0.004
"""Free space (m) left between the hand and a part when the hand arrives in its vicinity."""
LID_PRESS_INSET = 0.03
"""How far behind the lid's front edge the hand presses a lid down (m)."""
CLEAR_X = -0.12
"""x (m) of the free corridor in front of every can the hand travels through."""
GRASP_CLEARANCE = 0.08
"""How far above the ball (m) the hand comes down from to grasp it."""


class SkillError(ValueError):
    """A skill request that cannot be carried out (refused before the world is touched)."""


@dataclass(frozen=True)
class SkillResult:
    """Outcome of one arm skill ``action(part, θ)`` measured from ground truth."""

    action: str
    part: str
    theta: float
    part_displacement: float
    opening_before: float
    opening_after: float
    effect: float


def check_skill(world: GarbageWorld, action: str, part: str, theta: float) -> float:
    """Validate a skill request; return θ as a float or raise ``SkillError`` saying why."""
    if action not in ACTION_TYPES:
        raise SkillError(f"unknown action {action!r}; known actions: {', '.join(ACTION_TYPES)}")
    if part not in world.parts:
        raise SkillError(f"can {world.can} has no part {part!r}; its parts are "
                         f"{', '.join(world.parts)}")
    if isinstance(theta, bool) or not isinstance(theta, numbers.Real):
        raise SkillError(f"theta must be a number of metres, got {theta!r}")
    value = float(theta)
    lo, hi = THETA_BOUNDS[action]
    if not (math.isfinite(value) and lo < value <= hi):
        raise SkillError(f"theta {theta} m out of bounds for {action}: need {lo} < theta <= {hi}")
    return value


def _approach(world: GarbageWorld, action: str, part: str) -> list[np.ndarray]:
    """Waypoints from the free corridor to the start point of ``action`` on ``part``."""
    grip = world.model.geom(_grip_geom(world, part)).id
    centre = world.data.geom_xpos[grip].copy()
    half = world.model.geom_size[grip].copy()
    axes = world.data.geom_xmat[grip].reshape(3, 3)
    direction = np.array(ACTION_DIRECTIONS[action])
    if part == "lid" and action == "sweep_down":  # press on the lid's top, near its front
        top = _lid_top_front(world)
        high = top[2] + 0.08
        return [np.array([CLEAR_X, top[1], high]), np.array([top[0], top[1], high]), top]
    if not _is_bar(world, part):
        normal = axes[:, 0] if axes[0, 0] >= 0 else -axes[:, 0]
        start = centre - normal * (half[0] + HAND_RADIUS + MARGIN)
        return [np.array([CLEAR_X, start[1], start[2]]), start]
    start = centre - direction * (half @ np.abs(direction) + HAND_RADIUS + MARGIN)
    if action == "contract_arm":  # the gap behind the bar is reached from below the bar
        below = centre[2] - half[2] - HAND_RADIUS - MARGIN
        return [np.array([CLEAR_X, start[1], below]), np.array([start[0], start[1], below]),
                start]
    return [np.array([CLEAR_X, start[1], start[2]]), start]


def _is_bar(world: GarbageWorld, part: str) -> bool:
    """Parts that stand off the can and are gripped from a side: a handle, a pedal, the tab
    on a sliding lid's front edge (a flat face is approached on its face instead)."""
    return part in ("handle", "pedal") or (part == "lid" and world.spec.mechanism == "slide_lid")


def _grip_geom(world: GarbageWorld, part: str) -> str:
    """The box the hand works around: the part's marker, or the tab behind a sliding lid's."""
    return "tab" if part == "lid" and world.spec.mechanism == "slide_lid" else f"marker_{part}"


def _lid_top_front(world: GarbageWorld) -> np.ndarray:
    """Point just above the lid's top face, a little behind its front edge (world frame)."""
    geom = world.model.geom("lid_shell").id
    half = world.model.geom_size[geom]
    axes = world.data.geom_xmat[geom].reshape(3, 3)
    local = np.array([-half[0] + LID_PRESS_INSET, 0.0, half[2] + HAND_RADIUS + MARGIN])
    return world.data.geom_xpos[geom] + axes @ local


def perform_skill(world: GarbageWorld, action: str, part: str, theta: float) -> SkillResult:
    """Approach ``part``, move the hand by ``theta`` m as ``action``, withdraw and measure."""
    value = check_skill(world, action, part, theta)
    before = world.state()
    waypoints = _approach(world, action, part)
    for point in waypoints:
        world.move_arm_to(point)
    start = world.setpoint
    world.move_arm_to(start + np.array(ACTION_DIRECTIONS[action]) * value)
    world.move_arm_to(start)
    for point in reversed(waypoints[:-1]):
        world.move_arm_to(point)
    world.home()
    world.settle()
    after = world.state()
    moved = np.subtract(after.parts[part].pos, before.parts[part].pos)
    return SkillResult(
        action=action,
        part=part,
        theta=value,
        part_displacement=float(np.linalg.norm(moved)),
        opening_before=before.opening,
        opening_after=after.opening,
        effect=after.opening - before.opening,
    )


def ball_within_reach(world: GarbageWorld) -> bool:
    """Whether the hand can take the ball where it lies: the grip point and the point above it
    it comes down from are inside the arm's reach, and the ball is not in the can."""
    state = world.state()
    if state.ball_in_can:
        return False
    grip = np.array(state.ball_pos) - np.array([GRIP_OFFSET, 0.0, 0.0])
    low = np.array([bound[0] for bound in ARM_RANGE])
    high = np.array([bound[1] for bound in ARM_RANGE])
    above = grip + np.array([0.0, 0.0, GRASP_CLEARANCE])
    return bool(np.all(grip >= low) and np.all(above <= high))


def grasp_ball(world: GarbageWorld) -> bool:
    """Reach the ball from above, close the hand on it and lift it; True if it is held."""
    if world.state().holding_ball:
        return True
    ball = np.array(world.state().ball_pos)
    grip = ball - np.array([GRIP_OFFSET, 0.0, 0.0])
    world.move_arm_to(grip + np.array([0.0, 0.0, GRASP_CLEARANCE]))
    world.move_arm_to(grip)
    held = world.grasp()
    world.move_arm(0.0, 0.0, 0.10)
    world.home()
    return held and world.state().holding_ball


@dataclass(frozen=True)
class DropResult:
    """What became of a dropped ball: ``landed`` in the can, or not; ``blocked`` if the can
    stopped the ball at its front edge before it was over the opening."""

    landed: bool
    blocked: bool


def _handle_top(world: GarbageWorld) -> float:
    """World height (m) of the top of the can's handle, -inf for a can without one: a
    handle high on the front face, lifted far, stands over the rim in the ball's way."""
    if "handle" not in world.parts:
        return -math.inf
    m, d = world.model, world.data
    body = m.body("handle").id
    return max(float(d.geom_xpos[g][2] + np.abs(d.geom_xmat[g].reshape(3, 3)[2]) @ m.geom_size[g])
               for g in range(m.ngeom) if m.geom_bodyid[g] == body)


def drop_ball(world: GarbageWorld) -> DropResult:
    """Carry the held ball into the can's opening and let go.

    The hand slides the ball in just above the rim, at the stretch of the front edge the lid
    leaves most open (``GarbageWorld.free_rim_y``: the middle for a lid that lifts, the
    uncovered side for one that slides away), or just above a handle that a lift left
    standing over the rim; the move is guarded, so a closed (or not open enough) lid stops
    the ball at the can and it is dropped there, outside. Without a ball in hand nothing
    moves (neither landed nor blocked).
    """
    if not world.state().holding_ball:
        return DropResult(landed=False, blocked=False)
    y = world.free_rim_y()
    z = max(world.spec.rim, _handle_top(world)) + BALL_RADIUS + 0.006
    inside = np.array([WALL + BALL_RADIUS + 0.006 - GRIP_OFFSET, y, z])
    outside = np.array([CLEAR_X + 0.04 - GRIP_OFFSET, y, z])
    world.move_arm_to(outside)
    world.set_ball_collisions(True)
    blocked = not world.move_arm_to(inside, stop_if=world.ball_touches_can)
    world.drop()
    world.move_arm_to(np.array([outside[0], y, world.effector_pos[2]]))
    world.home()
    world.settle()
    return DropResult(landed=world.state().ball_in_can, blocked=blocked)
