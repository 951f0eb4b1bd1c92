"""The simulated can as an object under test for the chapter-5 learners (behaviours/learners).

``CanUnderTest`` wraps a ``GarbageWorld`` and a perception (camera or truth): ``perceive``
gives the parts' Table 5.1 descriptors, ``above`` relations and the opening s_o (eq. 5.14);
``perform(part, action, θ)`` puts the can back in the state it had when learning began (the
thesis's lid is closed before every try, §5.6.1), runs the motor skill and measures the part's
displacement (eq. 5.15) and the opening before and after, as the perception sees them. It
counts every action it performs.
"""

from __future__ import annotations

from collections.abc import Mapping

from behaviours.learners.protocol import ObjectView, Outcome
from behaviours.perception import Perception, part_displacement
from behaviours.skills import THETA_BOUNDS, perform_skill
from sim.world import GarbageWorld


class CanUnderTest:
    """One simulated can, seen through ``perception``, acted on by the motor skills."""

    def __init__(self, world: GarbageWorld, perception: Perception,
                 actions: Mapping[str, tuple[float, float]] = THETA_BOUNDS) -> None:
        self.world = world
        self.perception = perception
        self.name = world.can
        self.actions = dict(actions)
        self.initial_opening = world.opening()
        self.performed = 0

    def perceive(self) -> ObjectView:
        """The can as it stands now: parts, descriptors, relations, image positions, s_o."""
        seen = self.perception.observe(self.world)
        return ObjectView(
            parts={name: part.descriptor() for name, part in seen.parts.items()},
            above=frozenset(seen.above),
            positions={name: part.centre for name, part in seen.parts.items()},
            state=seen.opening,
        )

    def perform(self, part: str, action: str, theta: float) -> Outcome:
        """Reset the can to its initial opening, do action(θ) on part, measure (5.3, 5.15)."""
        self.world.set_opening(self.initial_opening)
        before = self.perception.observe(self.world)
        perform_skill(self.world, action, part, theta)
        self.performed += 1
        after = self.perception.observe(self.world)
        moved = part_displacement(before, after, part)
        return Outcome(part_displacement=moved, state_before=before.opening,
                       state_after=after.opening)

    def restore(self) -> None:
        """Leave the can as learning found it."""
        self.world.set_opening(self.initial_opening)
