"""Algorithm 1 (thesis §3.3.2): an affordance table of (object, action, effect) triples.

The table is a short-term memory with the simplest forgetting: an observed triple (o, a, e) is
added when no triple for (o, a) is known, and replaces the known one otherwise, so the robot
follows a world whose affordances change. Triples keep the order in which their (o, a) was
first met (Table 3.3 numbers them so). ``undesired_actions`` is the filter of eq. 3.10: the
actions whose known effect on an object is one of the undesired effects.

Objects and actions are bit strings (``"1001"``, ``"010"``), effects small integers (1 moved,
0 unmoved, §3.5.2), so a saved table reads like Table 3.3. It is a plain dict rather than a
scikit-learn estimator because Algorithm 1 is exactly a dict update; the file format is the
learners' versioned JSON (``persist``), written atomically.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from pathlib import Path

from behaviours.learners.persist import LearnerFileError, read_learner, write_learner

__all__ = ["AffordanceTable", "LearnerFileError"]

KIND = "affordance_table"


def _bits(value: object, what: str) -> str:
    """``value`` if it is a non-empty string of 0s and 1s, else ValueError naming ``what``."""
    if not isinstance(value, str) or not value or set(value) - {"0", "1"}:
        raise ValueError(f"{what} must be a string of 0s and 1s, got {value!r}")
    return value


def _effect(value: object) -> int:
    """``value`` if it is an integer effect, else ValueError."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise ValueError(f"an effect must be an integer (1 moved, 0 unmoved), got {value!r}")
    return value


class AffordanceTable:
    """The table [T] of Algorithm 1 and the filter of eq. 3.10."""

    def __init__(self, undesired_effects: tuple[int, ...] = (0,)):
        """``undesired_effects``: the set E of eq. 3.10 (default: "unmoved")."""
        self.undesired_effects = undesired_effects
        self.triples_: dict[tuple[str, str], int] = {}

    def update(self, obj: str, action: str, effect: int) -> bool:
        """Algorithm 1, lines 6-10: add (o, a, e), or replace the effect known for (o, a).

        Returns True when the table changed (a new pair, or a different effect).
        """
        key = (_bits(obj, "an object"), _bits(action, "an action"))
        value = _effect(effect)
        changed = self.triples_.get(key) != value
        self.triples_[key] = value
        return changed

    def effect(self, obj: str, action: str) -> int | None:
        """The effect known for ``action`` on ``obj``, or None if it was never tried."""
        return self.triples_.get((obj, action))

    def undesired_actions(self, obj: str, actions: Iterable[str]) -> set[str]:
        """Eq. 3.10: those of ``actions`` whose known effect on ``obj`` is undesired."""
        return {a for a in actions if self.triples_.get((obj, a)) in self.undesired_effects}

    def triples(self) -> list[tuple[str, str, int]]:
        """Every (object, action, effect), in the order the pairs were first met."""
        return [(o, a, e) for (o, a), e in self.triples_.items()]

    def __len__(self) -> int:
        """How many (object, action) pairs the table knows."""
        return len(self.triples_)

    # ------------------------------------------------------------------ files
    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write the table atomically (Algorithm 1, line 1 loads it again)."""
        return write_learner(path, KIND, {"undesired_effects": list(self.undesired_effects)},
                             {"triples": [list(t) for t in self.triples()]})

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> AffordanceTable:
        """A table saved by ``save``; a file that is not one is a ``LearnerFileError``."""
        params, state = read_learner(path, KIND)  # the schema checked every field
        try:
            table = cls(tuple(params["undesired_effects"]))
            for row in state["triples"]:
                table.update(*row)
        except ValueError as error:
            raise LearnerFileError(f"affordance table {str(path)!r} is corrupt: "
                                   f"{error}") from None
        return table
