"""What the chapter 4 reproductions share: the four configurations and one exploration run.

A configuration is a can and the part the hand holds (thesis §4.6: the push-lid can, our o1,
and the pull-handle can, our o5) with 1-D (Δx) or 3-D (Δx, Δy, Δz) actions and its budget N_s
(100 for 1-D, 300 for 3-D). ``explore`` runs Algorithm 3 or the random baseline on a fresh
world through ``behaviours.contact.PartContact``; the same seed gives both methods the same
first 20 random actions.
"""

from __future__ import annotations

import math
import statistics
from dataclasses import dataclass

import numpy as np

CONFIGURATIONS = ("lid-1d", "lid-3d", "handle-1d", "handle-3d")
METHODS = ("active", "random")


@dataclass(frozen=True)
class Configuration:
    """One of Figs 4.6–4.9: which can, which part, how many action dimensions, N_s."""

    name: str
    can: str
    part: str
    dims: int
    budget: int


SETUPS = {
    "lid-1d": Configuration("lid-1d", "o1", "lid", 1, 100),
    "lid-3d": Configuration("lid-3d", "o1", "lid", 3, 300),
    "handle-1d": Configuration("handle-1d", "o5", "handle", 1, 100),
    "handle-3d": Configuration("handle-3d", "o5", "handle", 3, 300),
}
N_RANDOM = 20
"""The first actions are random in both methods (thesis §4.6.1: N = 20)."""
TOLERANCE = 1e-4
"""ε of (4.10) (thesis §4.6.1)."""


def budget(setup: Configuration, scale: float) -> int:
    """N_s shrunk by ``scale``, never below N + 2 (the least that lets (4.10) be tested)."""
    return max(N_RANDOM + 2, round(setup.budget * scale))


def explore(setup: Configuration, method: str, seed: int, scale: float, perception: str,
            stop: bool):
    """One exploration of ``setup`` by ``method`` on a fresh world: the fitted ActiveExplorer.

    The world is left as the exploration left it (the caller may go on using it).
    """
    from behaviours.contact import CONTACT_CAMERA, PartContact
    from behaviours.learners.exploration import ActiveExplorer
    from behaviours.perception import make_perception
    from sim.world import GarbageWorld

    world = GarbageWorld(setup.can, seed=seed)
    contact = PartContact(world, setup.part, dims=setup.dims,
                          perception=make_perception(perception, CONTACT_CAMERA))
    contact.start()
    explorer = ActiveExplorer(mode=method, n_max=budget(setup, scale), n_random=N_RANDOM,
                              random_state=seed, stop=stop).explore(contact)
    return explorer, contact


def rounded(values: np.ndarray, digits: int = 6) -> list:
    """A float array as JSON lists, NaN as None."""
    return [None if isinstance(v, float) and math.isnan(v) else v
            for v in np.round(np.asarray(values, dtype=float), digits).tolist()]


def median_or_none(values: list[int]) -> float | None:
    """The median of the values, None when there are none."""
    return float(statistics.median(values)) if values else None
