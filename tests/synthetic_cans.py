"""Hand-made objects under test for the chapter-5 learners: linear parts, no physics engine.

Each ``SyntheticCan`` has parts with Table 5.1-like descriptors (the values the simulated
cans show to the head camera), ``above`` relations, and a few working (part, action) pairs:
the part moves ``gain`` m per m of θ (up to ``limit``) and the opening grows ``opening`` m
per m of part displacement. Every other pair moves nothing. ``perform`` counts its calls.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from behaviours.learners.protocol import ObjectView, Outcome

ACTIONS = {a: (0.0, 0.1) for a in ("extend_arm", "contract_arm", "sweep_left", "sweep_right",
                                   "lift_up", "sweep_down")}
LID = (0.0021, 0.4, 1.0)
LOW_LID = (0.0016, 0.3889, 1.0)
BODY = (0.0047, 0.4643, 1.0)
HANDLE = (0.0059, 0.3158, 1.0)
PEDAL = (0.0030, 0.95, 1.0)
HANDLE_CAN = {("lid", "body"), ("lid", "handle"), ("handle", "body")}


@dataclass(frozen=True)
class Working:
    """A pair that moves its part (gain m/m of θ, at most limit m) and opens the can."""

    gain: float
    opening: float
    limit: float = np.inf


@dataclass
class SyntheticCan:
    """An object under test whose pairs respond linearly (plus optional noise)."""

    name: str
    parts: dict[str, tuple[float, float, float]]
    above: set[tuple[str, str]]
    working: dict[tuple[str, str], Working]
    noise: float = 0.0
    seed: int = 0
    actions: dict[str, tuple[float, float]] = field(default_factory=lambda: dict(ACTIONS))
    calls: list[tuple[str, str, float]] = field(default_factory=list)

    def __post_init__(self) -> None:
        self._rng = np.random.default_rng(self.seed)

    def perceive(self) -> ObjectView:
        return ObjectView(parts={p: np.array(d) for p, d in self.parts.items()},
                          above=frozenset(self.above), state=0.0)

    def perform(self, part: str, action: str, theta: float) -> Outcome:
        self.calls.append((part, action, theta))
        rule = self.working.get((part, action))
        moved = 0.0 if rule is None else min(rule.gain * theta, rule.limit)
        opened = 0.0 if rule is None else rule.opening * moved
        if self.noise:
            moved = abs(moved + self._rng.normal(0.0, self.noise))
            opened = max(0.0, opened + self._rng.normal(0.0, self.noise))
        return Outcome(part_displacement=moved, state_before=0.0, state_after=opened)


def thesis_cans(noise: float = 0.0, seed: int = 0) -> dict[str, SyntheticCan]:
    """Five cans shaped like the simulated o1..o5 (push lid, lift handle, push, lift, pull)."""
    def can(name, parts, above, working):
        return SyntheticCan(name, parts, set(above), working, noise=noise, seed=seed)

    two = {"lid": LID, "body": BODY}
    three = {"lid": LOW_LID, "body": BODY, "handle": HANDLE}
    return {
        "o1": can("o1", two, {("lid", "body")}, {("lid", "extend_arm"): Working(1.2, 0.93)}),
        "o2": can("o2", three, HANDLE_CAN, {("handle", "lift_up"): Working(0.93, 2.07)}),
        "o3": can("o3", two, {("lid", "body")}, {("lid", "extend_arm"): Working(2.3, 0.81)}),
        "o4": can("o4", {**three, "lid": (0.0019, 0.4444, 1.0)}, HANDLE_CAN,
                  {("handle", "lift_up"): Working(0.92, 3.4)}),
        "o5": can("o5", three, HANDLE_CAN, {("handle", "contract_arm"): Working(0.91, 1.66)}),
    }
