"""The hand keeping hold of a can's part: one job of ``GarbageWorld`` (sim/world.py).

``HandHold`` switches the scene's ``hold_<part>`` equality constraints (a ball joint between
the hand and the point of the part it touches) on and off, and keeps a sliding hold's anchor
under the hand between physics steps. It is a mixin: the world it is mixed into gives the
model, the data, the can's name and parts, the hand's position and ``relax`` (aim the arm
where the hand is and settle).
"""

from __future__ import annotations

import mujoco
import numpy as np

from sim.scene import HOLD_SOLREF, HOLDABLE

HOLD_REACH = 0.01
"""The hand takes hold of a part only if it is at most this far (m) from the part's surface."""
SLIDING_SOLREF = (-44000.0, -2.0)
"""A sliding hold's constraint (MuJoCo's direct solref: stiffness, damping): as stiff as the
ball joint's (timeconst 0.005 s) but nearly undamped, since the damping would also act along
the face and drag the sliding hand (moved ~2 mm of a 1 cm step instead of ~8 mm)."""

SlidingHold = tuple[int, np.ndarray, np.ndarray, tuple[np.ndarray, np.ndarray]]
"""A sliding hold: its equality's id, the held body's frame (the transpose of its rotation
matrix and its origin, views of the data that every physics step updates) and the (y, z)
bounds of its face."""


class HandHold:
    """Holding a part with the hand, firmly or sliding over its face (mixin of a world)."""

    model: mujoco.MjModel
    data: mujoco.MjData
    can: str
    parts: tuple[str, ...]
    effector_pos: np.ndarray

    def _reset_holds(self) -> None:
        """Find the current model's hold constraints and let go of everything (after a reset
        or a new model)."""
        m, d = self.model, self.data
        self._holds = {part: mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_EQUALITY, f"hold_{part}")
                       for part in HOLDABLE if part in self.parts}
        for hold in self._holds.values():
            d.eq_active[hold] = 0
        self._sliding: SlidingHold | None = None

    def _follow_hand(self) -> None:
        """Before a physics step: a sliding hold's anchor moves over the face to where the
        hand is (its depth stays)."""
        if self._sliding is None:
            return
        eq, rotation_t, origin, (lo, hi) = self._sliding
        local = rotation_t @ (self.effector_pos - origin)
        # np.clip's own two ufuncs, called directly: this runs before every physics step
        self.model.eq_data[eq, 4:6] = np.minimum(np.maximum(local[1:], lo), hi)

    @property
    def held_part(self) -> str | None:
        """The part the hand keeps hold of, if any (see ``hold``)."""
        return next((p for p, eq in self._holds.items() if self.data.eq_active[eq]), None)

    def hold(self, part: str, sliding: bool = False) -> None:
        """Keep hold of ``part`` at the point the hand touches: a ball joint from now on.

        The hand must be within ``HOLD_REACH`` of the part (approach it first). While held,
        the part follows the hand as far as its own joint lets it, both ways: the hand that
        pushed a lid open can pull it shut again (thesis ch. 4's paired skills).
        ``sliding``: keep only the hand's distance from the part's front face (the plane
        across the part's own x axis), and let the hand slide over the face, within its
        edges: a hand pressed on a lid that rests against it, as NAO's hand on the push-lid
        (thesis §4.6), rather than one gripping a point of it.
        """
        if part not in self._holds:
            held = ", ".join(self._holds) or "nothing"
            raise ValueError(f"can {self.can} has no part {part!r} to hold; it has {held}")
        if self.held_part is not None:
            raise ValueError(f"the hand already holds the {self.held_part}; release it first")
        gap = _distance_to(self.model, self.data, part)
        if gap > HOLD_REACH:
            raise ValueError(f"the hand is {gap:.3f} m from the {part}; it must be within "
                             f"{HOLD_REACH} m to take hold (approach the part first)")
        m, d = self.model, self.data
        body = m.body(part).id
        eq = self._holds[part]
        m.eq_data[eq, 0:3] = 0.0  # the hand's centre ...
        offset = self.effector_pos - d.xpos[body]
        m.eq_data[eq, 3:6] = d.xmat[body].reshape(3, 3).T @ offset  # ... where it is on the part
        m.eq_solref[eq] = SLIDING_SOLREF if sliding else HOLD_SOLREF
        d.eq_active[eq] = 1
        self._sliding = ((eq, d.xmat[body].reshape(3, 3).T, d.xpos[body], _face_extent(m, body))
                         if sliding else None)
        self.relax()

    def release(self) -> None:
        """Let go of the held part (nothing happens if none is held)."""
        for eq in self._holds.values():
            self.data.eq_active[eq] = 0
        self._sliding = None
        self.relax()


def _distance_to(model: mujoco.MjModel, data: mujoco.MjData, part: str) -> float:
    """Smallest distance (m) between the hand and the colliding geoms of ``part``."""
    hand = model.geom("hand").id
    body = model.body(part).id
    geoms = [g for g in range(model.ngeom)
             if model.geom_bodyid[g] == body and model.geom_contype[g]]
    return min(mujoco.mj_geomDistance(model, data, hand, g, 1.0, None) for g in geoms)


def _face_extent(model: mujoco.MjModel, body: int) -> tuple[np.ndarray, np.ndarray]:
    """(y, z) bounds, in ``body``'s frame, of its colliding geoms: the face a hand slides on."""
    lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
    for g in range(model.ngeom):
        if model.geom_bodyid[g] == body and model.geom_contype[g]:
            centre, half = model.geom_pos[g][1:], model.geom_size[g][1:]
            lo, hi = np.minimum(lo, centre - half), np.maximum(hi, centre + half)
    return lo, hi
