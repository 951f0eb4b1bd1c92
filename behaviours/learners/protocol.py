"""The "object under test" that the chapter-5 learners act on, and what they record of it.

An ``ObjectUnderTest`` is anything with parts that can be perceived and acted on: the
simulated can of ``sim/``, a hand-made test object, a real robot. The learners only ever
``perceive()`` it and ``perform(part, action, θ)`` on it, so they run on any world, and every
physical action passes through ``perform``, where it is counted (thesis eq. 5.13: N).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from behaviours.learners.part_models import Bounds


@dataclass(frozen=True)
class ObjectView:
    """What the robot perceives of an object before acting (thesis §5.3.1).

    ``parts`` maps each part to its Table 5.1 descriptor (area, rectangleness, squareness);
    ``above`` holds the pairs (ψ_i, ψ_j) with ψ_i above ψ_j in the image (§5.5.3);
    ``positions`` is each part's state s_ψ (its image position); ``state`` is s_o.
    """

    parts: Mapping[str, np.ndarray]
    above: frozenset[tuple[str, str]] = frozenset()
    positions: Mapping[str, tuple[float, ...]] = field(default_factory=dict)
    state: float = 0.0


@dataclass(frozen=True)
class Outcome:
    """What one action did: the part's displacement e_ψ (5.15) and s_o before and after."""

    part_displacement: float
    state_before: float
    state_after: float

    @property
    def effect(self) -> float:
        """e_o = s'_o - s_o (eq. 5.3)."""
        return self.state_after - self.state_before


class ObjectUnderTest(Protocol):
    """An object the learners can perceive and act on.

    ``perform`` must present the object in its initial state s_o^i for every action (the
    thesis's lid is closed before each try, §5.6.1), act, and report what happened.
    """

    name: str
    actions: Mapping[str, Bounds]  # each action type and its parameter bounds lo < θ <= hi

    def perceive(self) -> ObjectView:
        """Parts, their descriptors and relations, and s_o, as seen now."""
        ...

    def perform(self, part: str, action: str, theta: float) -> Outcome:
        """Do ``action(θ)`` on ``part`` from the initial state; report the outcome."""
        ...


@dataclass(frozen=True)
class Trial:
    """One physical action a learner took, why, and what it did (a data tuple 5.6 and more)."""

    part: str
    action: str
    theta: float
    part_displacement: float
    effect: float
    state_after: float
    purpose: str
    """explore (Algorithm 4), transfer (Alg. 6 line 10, k = 1), gradient (line 13),
    exploit (5.11/5.12 on the object's own models), or consistency (lines 18, 28)."""
    reached: bool
