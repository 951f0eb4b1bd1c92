"""Algorithm 2 (thesis §3.3.4): XCS whose action choice skips what the affordance table says
will not work (eq. 3.10), while the table learns from every push (Algorithm 1).

``AffordanceXCS`` wraps any task learner with XCS's multi-step interface (``act(state,
explore, allowed, considered=...)``, ``reward(r, done)``, ``end_trial()``): before each choice
it asks the table which actions have an undesired known effect on the object in front and
passes the others as ``allowed`` (lines 5-8). Where the filter reaches is ``filter_scope``:

- ``"choice"`` (Algorithm 2 as printed): lines 3-4 form [M] and the prediction array the
  standard way and line 6 filters only the candidates of line 8's choice, so covering and the
  max of eq. 7.2 range over every applicable action;
- ``"choice_and_value"``: the filtered actions are also left out of covering and of eq. 7.2's
  max, as if they did not exist in that state (an earlier reading, kept as an option).

``applicable`` (a task's preconditions, §3.2.2: "preconditions of actions are provided as
domain knowledge") restricts everything, choice and value alike: an action that cannot be
applied in a state has no value there. With ``use_affordances=False`` it is standard XCS
that still records the table (the thesis's baseline, whose learned movability is reported all
the same). If the filter left no applicable action it is dropped for that step: an empty
choice would stall the robot.
"""

from __future__ import annotations

from collections.abc import Collection
from typing import Protocol

from behaviours.learners.affordance_table import AffordanceTable

__all__ = ["FILTER_SCOPES", "AffordanceXCS", "TaskLearner"]

FILTER_SCOPES = ("choice", "choice_and_value")
"""Where eq. 3.10's filter applies: line 8's choice only (Algorithm 2), or also covering and
eq. 7.2's max."""


class TaskLearner(Protocol):
    """The multi-step interface of ``behaviours.learners.xcs.XCS``."""

    def act(self, state: object, explore: bool = True, allowed: object = None, *,
            considered: object = None) -> int: ...
    def reward(self, r: float, done: bool) -> None: ...
    def end_trial(self) -> None: ...


class AffordanceXCS:
    """A task learner, an affordance table [T] and the eq. 3.10 filter between them."""

    def __init__(self, learner: TaskLearner, actions: tuple[str, ...],
                 table: AffordanceTable | None = None, use_affordances: bool = True,
                 filter_scope: str = "choice"):
        """``actions``: the action bit strings in the learner's index order (Table 3.1)."""
        if filter_scope not in FILTER_SCOPES:
            raise ValueError(f"unknown filter_scope {filter_scope!r}; use "
                             f"{' or '.join(FILTER_SCOPES)}")
        self.learner = learner
        self.actions = actions
        self.table = AffordanceTable() if table is None else table
        self.use_affordances = use_affordances
        self.filter_scope = filter_scope

    def allowed(self, obj: str | None,
                applicable: Collection[int] | None = None) -> set[int] | None:
        """Indices of the applicable actions not filtered on ``obj`` (None: every action)."""
        candidates = set(range(len(self.actions)) if applicable is None else applicable)
        if self.use_affordances and obj is not None:
            blocked = self.table.undesired_actions(obj, self.actions)
            kept = {i for i in candidates if self.actions[i] not in blocked}
            candidates = kept or candidates
        return None if len(candidates) == len(self.actions) else candidates

    def act(self, state: str, obj: str | None, explore: bool,
            applicable: Collection[int] | None = None) -> int:
        """Lines 2-8: choose an action index for ``state`` with ``obj`` in front, among the
        ``applicable`` ones (None: all)."""
        allowed = self.allowed(obj, applicable)
        if allowed is None and applicable is None:  # nothing filtered: plain XCS
            return self.learner.act(state, explore=explore)
        if self.filter_scope == "choice_and_value":  # eq. 7.2 and covering see `allowed` only
            return self.learner.act(state, explore=explore, allowed=allowed)
        considered = range(len(self.actions)) if applicable is None else applicable
        return self.learner.act(state, explore=explore, allowed=allowed, considered=considered)

    def observe_effect(self, obj: str, action: int, effect: int) -> None:
        """Line 11 (Algorithm 1): remember what ``action`` did to ``obj``."""
        self.table.update(obj, self.actions[action], effect)

    def reward(self, r: float, done: bool) -> None:
        """Lines 12-14: credit the action set with the reward."""
        self.learner.reward(r, done)

    def end_trial(self) -> None:
        """A trial cut short by its step limit (n_step): no terminal reward."""
        self.learner.end_trial()
