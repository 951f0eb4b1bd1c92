"""Chapter 4's continuous interface to a garbage can: the hand holds a part and moves in steps.

``PartContact`` is a ``behaviours.learners.exploration.ContinuousWorld`` over a simulated can
(thesis §4.6.1): the hand approaches the lid (push-lid can) or the handle (pull-handle can),
keeps hold of it where it touches (``GarbageWorld.hold``), and every step moves by
a = (Δx, Δy, Δz), each in [−0.01, 0.01] m (1-D: Δx only); the state is s_o, the share of the
head-camera image taken by the dark opening (eq. 4.19), seen by the camera or computed from
ground truth; the effect is s'_o − s_o (eq. 4.20). Holding (rather than pushing a free face)
is what lets the same hand close a hinged lid again by moving back: the paired skills of §4.5.
"""

from __future__ import annotations

from types import TracebackType

import numpy as np

from behaviours.perception import Perception, TruthPerception
from behaviours.skills import CLEAR_X, _approach
from sim.world import GarbageWorld

__all__ = ["CONTACT_STEP", "PartContact"]

CONTACT_STEP = 0.01
"""Largest move (m) per dimension and step (thesis: −0.01 ≤ Δx, Δy, Δz ≤ 0.01)."""


class PartContact:
    """Hold ``part`` of the world's can and move the hand by small steps (a ContinuousWorld).

    Use as a context manager, or call ``start`` and ``finish``: ``start`` approaches the part
    and takes hold, ``finish`` lets go and takes the hand home (the part stays where it is).
    """

    def __init__(self, world: GarbageWorld, part: str, *, dims: int = 1,
                 perception: Perception | None = None) -> None:
        """``dims`` is 1 (Δx) or 3 (Δx, Δy, Δz); ``perception`` defaults to ground truth."""
        if dims not in (1, 3):
            raise ValueError(f"dims must be 1 (Δx) or 3 (Δx, Δy, Δz), got {dims!r}")
        if part not in world.parts:
            raise ValueError(f"can {world.can} has no part {part!r}; its parts are "
                             f"{', '.join(world.parts)}")
        self.world = world
        self.part = part
        self.dims = dims
        self.perception = perception if perception is not None else TruthPerception()
        self._seen: float | None = None  # s_o after the last step: the world has not moved since

    @property
    def action_bounds(self) -> list[tuple[float, float]]:
        """[−0.01, 0.01] m per action dimension."""
        return [(-CONTACT_STEP, CONTACT_STEP)] * self.dims

    def start(self) -> PartContact:
        """Approach the part's face (in front of a handle's bar) and take hold of it."""
        for point in _approach(self.world, "extend_arm", self.part):
            self.world.move_arm_to(point)
        self.world.hold(self.part)
        self._seen = None
        return self

    def finish(self) -> None:
        """Let go, back out in front of the can and go home; the part stays where it is."""
        self.world.release()
        self._seen = None
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
        """Move the held part by ``action`` (m per dimension) and return the new s_o."""
        if self.world.held_part != self.part:
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
        self.world.move_arm(*delta)
        self.world.relax()
        self._seen = None
        return self.observe()
