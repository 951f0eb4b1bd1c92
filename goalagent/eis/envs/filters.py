"""When a percept reaches an agent: EIS2Java's percept filters, per entity.

Java environments written with EIS2Java mark each percept with a filter. The agent sees, per
perceive call (the percepts of one reasoning cycle):

- ``ALWAYS``: every current value, every call;
- ``ONCE``: the values of the first call only (e.g. BW4T's map, the elevator's capacity);
- ``ON_CHANGE``: EIS 0.7 (BW4T 3.9+): the current values that were not there last call;
  EIS 0.5 and older (BW4T 3.8 and BW4T 2): all current values if any differ from last call;
- ``ON_CHANGE_NEG`` (EIS 0.5 and older only): values new since last call, and ``not(V)`` for
  every value that was there last call and is gone.

``PerceptFilter`` keeps the previous values per entity and percept name, as EIS2Java keeps
them per entity and percept method. Values are the percepts' argument tuples (compared as
Python values, cheaper than building percepts that are not sent); ``percepts`` builds the
ones that are.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable
from enum import Enum

from goalagent.eis.terms import Function, Percept


class Filter(Enum):
    """How often a percept is sent; see the module docstring."""

    ALWAYS = "always"
    ONCE = "once"
    ON_CHANGE = "on change"
    ON_CHANGE_NEG = "on change with negation"


class PerceptFilter:
    """Previous values per (entity, percept name), and the filtering EIS2Java applies to them.

    Args:
        legacy: filter as EIS 0.5 did (``ON_CHANGE`` resends all values on a change,
            ``ON_CHANGE_NEG`` is allowed); otherwise as EIS 0.7.
    """

    def __init__(self, legacy: bool = False) -> None:
        self.legacy = legacy
        self._previous: dict[tuple[str, str], list[Percept]] = {}

    def reset(self, entity: str | None = None) -> None:
        """Forget what ``entity`` (or every entity) was sent, as after an environment reset."""
        if entity is None:
            self._previous.clear()
        else:
            self._previous = {key: v for key, v in self._previous.items() if key[0] != entity}

    def sent_once(self, entity: str, name: str) -> bool:
        """True when the ``ONCE`` percept ``name`` was already sent to ``entity``."""
        return (entity, name) in self._previous

    def apply(
        self, entity: str, name: str, kind: Filter, current: Iterable[Hashable]
    ) -> tuple[list[Hashable], list[Hashable]]:
        """The values of ``name`` that ``entity`` gets now, given the ``current`` values: those
        sent as they are, and those sent negated (``ON_CHANGE_NEG`` only)."""
        key = (entity, name)
        values = list(current)
        previous = self._previous.get(key)
        self._previous[key] = values
        if kind is Filter.ALWAYS:
            return values, []
        if kind is Filter.ONCE:
            return (values if previous is None else []), []
        before = previous or []
        if kind is Filter.ON_CHANGE:
            if self.legacy:
                return (values if values != before else []), []
            return [value for value in values if value not in before], []
        if not self.legacy:
            raise ValueError("ON_CHANGE_NEG exists only in EIS 0.5 and older (legacy filtering)")
        return ([value for value in values if value not in before],
                [value for value in before if value not in values])

    def percepts(self, entity: str, name: str, kind: Filter,
                 current: Iterable[tuple]) -> list[Percept]:
        """``apply`` for argument tuples, as percepts: ``name(Args...)``, ``not(name(...))``."""
        sent, negated = self.apply(entity, name, kind, current)
        result = [Percept.of(name, *args) for args in sent]
        for args in negated:
            percept = Percept.of(name, *args)
            result.append(Percept("not", (Function(name, percept.params),)))
        return result
