"""Chapter 4's continuous interface to a garbage can: the hand holds a part and moves in steps.

``PartContact`` is a ``behaviours.learners.exploration.ContinuousWorld`` over a simulated can
(thesis §4.6.1): the hand approaches the lid (push-lid can) or the handle (pull-handle can),
keeps hold of it (``GarbageWorld.hold``), and every step moves by a = (Δx, Δy, Δz), each in
[−0.01, 0.01] m (1-D: Δx only); the state is s_o, the share of the ``close`` camera's image
taken by the dark opening (eq. 4.19), seen by the camera or computed from ground truth; the
effect is s'_o − s_o (eq. 4.20). Holding (rather than pushing a free face) is what lets the
same hand close a hinged lid again by moving back: the paired skills of §4.5.

The set-up follows NAO's in §4.6 (the can 10–12 cm in front of the robot, Table 4.1):
- the hand presses on the lid's face and slides over it (a sliding hold: NAO's hand pushed
  the lid, it did not grip a point of it); it grips the handle's bar;
- the arm follows its targets as a position-controlled robot arm does (``CONTACT_STIFFNESS``;
  with the other chapters' softer arm a held lid's friction, acting through a short lever,
  stopped the hand 3–5 mm short of each 1 cm step);
- the arm's reach ends a few centimetres from where the hand took hold (``REACH``: fully
  stretched or fully contracted): pulled 6 cm, the handle has opened the can fully; pushed,
  the lid turns less and less as the hand slides up its face towards the hinge's height,
  and the arm is fully stretched 2.5 cm on. So either part is fully open after about 6 steps
  one way and fully closed (its own joint's limit) the other way, and the state then stays
  put, as §4.6.2 describes;
- s_o is seen by the ``close`` camera, from which a fully open can fills about 0.12 of the
  image, as the NAO's bottom camera saw it (Table 4.1: s_o up to 0.114–0.135).
"""

from __future__ import annotations

from types import TracebackType

import numpy as np

from behaviours.perception import Perception, TruthPerception
from behaviours.skills import CLEAR_X, _approach
from sim.scene import ARM_KP
from sim.world import GarbageWorld

__all__ = ["CONTACT_CAMERA", "CONTACT_STEP", "CONTACT_STIFFNESS", "REACH", "PartContact"]

CONTACT_STEP = 0.01
"""Largest move (m) per dimension and step (thesis: −0.01 ≤ Δx, Δy, Δz ≤ 0.01)."""
CONTACT_STIFFNESS = 15000.0
"""The arm's position-control stiffness (N/m) while it holds a part: a 1 cm step then moves
the hand 8–10 mm against a held part (the other chapters' 3000 N/m moved it 2–5 mm)."""
REACH = ((-0.06, 0.025), (-0.03, 0.03), (-0.03, 0.03))
"""How far (m) the hand can move from where it took hold, per axis (x, y, z): (contracted,
stretched). Pulling, the arm is fully contracted after six 1 cm steps, the handle fully
open; pushing the lid, it is fully stretched once its hand has gone 2.5 cm forward, about
where the lid stops turning (thesis: six 0.008 m pushes opened the lid, the arm stretched)."""
CONTACT_CAMERA = "close"
"""The camera s_o is measured in (see ``sim.scene.CLOSE_CAMERA_POS``)."""
SLIDING = {"lid": True, "handle": False}
"""Whether the hand slides over the part's face (the lid) or grips it (the handle's bar)."""


class PartContact:
    """Hold ``part`` of the world's can and move the hand by small steps (a ContinuousWorld).

    Use as a context manager, or call ``start`` and ``finish``: ``start`` approaches the part
    and takes hold, ``finish`` lets go and takes the hand home (the part stays where it is).
    """

    def __init__(self, world: GarbageWorld, part: str, *, dims: int = 1,
                 perception: Perception | None = None) -> None:
        """``dims`` is 1 (Δx) or 3 (Δx, Δy, Δz); ``perception`` defaults to ground truth
        seen from ``CONTACT_CAMERA``."""
        if dims not in (1, 3):
            raise ValueError(f"dims must be 1 (Δx) or 3 (Δx, Δy, Δz), got {dims!r}")
        if part not in world.parts:
            raise ValueError(f"can {world.can} has no part {part!r}; its parts are "
                             f"{', '.join(world.parts)}")
        self.world = world
        self.part = part
        self.dims = dims
        self.perception = perception if perception is not None else TruthPerception(
            CONTACT_CAMERA)
        self._seen: float | None = None  # s_o after the last step: the world has not moved since
        self._reach: tuple[np.ndarray, np.ndarray] | None = None

    @property
    def action_bounds(self) -> list[tuple[float, float]]:
        """[−0.01, 0.01] m per action dimension."""
        return [(-CONTACT_STEP, CONTACT_STEP)] * self.dims

    def start(self) -> PartContact:
        """Approach the part's face (in front of a handle's bar) and take hold of it; the
        arm stiffens and its reach is counted from here."""
        for point in _approach(self.world, "extend_arm", self.part):
            self.world.move_arm_to(point)
        self.world.arm_stiffness = CONTACT_STIFFNESS
        self.world.hold(self.part, sliding=SLIDING[self.part])
        hand = self.world.effector_pos
        self._reach = (hand + [lo for lo, _ in REACH], hand + [hi for _, hi in REACH])
        self._seen = None
        return self

    def finish(self) -> None:
        """Let go, back out in front of the can and go home; the part stays where it is."""
        self.world.release()
        self.world.arm_stiffness = ARM_KP
        self._seen = None
        self._reach = None
        hand = self.world.effector_pos
        self.world.move_arm_to([min(hand[0], CLEAR_X), hand[1], hand[2]])
        self.world.home()
        self.world.settle()

    def __enter__(self) -> PartContact:
        return self.start()

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.finish()

    def observe(self) -> float:
        """s_o (eq. 4.19) as the perception sees it now (the last step's view, if any)."""
        if self._seen is None:
            self._seen = self.perception.observe(self.world).opening_area
        return self._seen

    def step(self, action: np.ndarray) -> float:
        """Move the hand by ``action`` (m per dimension; no further than its reach) and return
        the new s_o."""
        if self.world.held_part != self.part or self._reach is None:
            raise ValueError(f"the hand does not hold the {self.part}; call start first")
        move = np.asarray(action, dtype=float).reshape(-1)
        if move.shape != (self.dims,) or not np.all(np.isfinite(move)):
            raise ValueError(f"an action is {self.dims} finite number(s) of metres, got "
                             f"{action!r}")
        if np.any(np.abs(move) > CONTACT_STEP + 1e-12):
            raise ValueError(f"action {move.tolist()} out of bounds: each component must lie "
                             f"in [-{CONTACT_STEP}, {CONTACT_STEP}] m")
        delta = np.zeros(3)
        delta[: self.dims] = move
        self.world.move_arm_to(np.clip(self.world.effector_pos + delta, *self._reach))
        self.world.relax()
        self._seen = None
        return self.observe()
