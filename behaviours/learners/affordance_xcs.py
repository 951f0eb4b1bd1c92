"""Algorithm 2 (thesis §3.3.4): XCS whose action choice skips what the affordance table says
will not work (eq. 3.10), while the table learns from every push (Algorithm 1).

``AffordanceXCS`` wraps any task learner with XCS's multi-step interface (``act(state,
explore, allowed)``, ``reward(r, done)``, ``end_trial()``): before each choice it asks the
table which actions have an undesired known effect on the object in front and passes the
others as ``allowed`` (lines 5-8), so exploration, exploitation and covering all avoid them.
With ``use_affordances=False`` it is standard XCS that still records the table (the thesis's
baseline, whose learned movability is reported all the same). If every action were filtered
the filter is dropped for that step: an empty choice would stall the robot.
"""

from __future__ import annotations

from typing import Protocol

from behaviours.learners.affordance_table import AffordanceTable

__all__ = ["AffordanceXCS", "TaskLearner"]


class TaskLearner(Protocol):
    """The multi-step interface of ``behaviours.learners.xcs.XCS``."""

    def act(self, state: object, explore: bool = True, allowed: object = None) -> int: ...
    def reward(self, r: float, done: bool) -> None: ...
    def end_trial(self) -> None: ...


class AffordanceXCS:
    """A task learner, an affordance table [T] and the eq. 3.10 filter between them."""

    def __init__(self, learner: TaskLearner, actions: tuple[str, ...],
                 table: AffordanceTable | None = None, use_affordances: bool = True):
        """``actions``: the action bit strings in the learner's index order (Table 3.1)."""
        self.learner = learner
        self.actions = actions
        self.table = AffordanceTable() if table is None else table
        self.use_affordances = use_affordances

    def allowed(self, obj: str | None) -> set[int] | None:
        """Indices of the actions not filtered on ``obj`` (None: no filter applies)."""
        if not self.use_affordances or obj is None:
            return None
        blocked = self.table.undesired_actions(obj, self.actions)
        if not blocked or len(blocked) == len(self.actions):
            return None
        return {i for i, a in enumerate(self.actions) if a not in blocked}

    def act(self, state: str, obj: str | None, explore: bool) -> int:
        """Lines 2-8: choose an action index for ``state`` with ``obj`` in front."""
        return self.learner.act(state, explore=explore, allowed=self.allowed(obj))

    def observe_effect(self, obj: str, action: int, effect: int) -> None:
        """Line 11 (Algorithm 1): remember what ``action`` did to ``obj``."""
        self.table.update(obj, self.actions[action], effect)

    def reward(self, r: float, done: bool) -> None:
        """Lines 12-14: credit the action set with the reward."""
        self.learner.reward(r, done)

    def end_trial(self) -> None:
        """A trial cut short by its step limit (n_step): no terminal reward."""
        self.learner.end_trial()
