"""The goal bases of one agent: a stack of them (a module's focus pushes one), adopt and
drop on the top one, and blind commitment: goals whose facts are all believed are removed.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from goalagent import ast
from goalagent.kb.prolog_modules import TRUE, PrologModules
from goalagent.kb.terms import Atom, Struct, Term

__all__ = ["GoalBases"]


class GoalBases(PrologModules):
    """The stack of goal bases in the agent's goal module; each goal is the list of its
    facts."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        # Goals adopted or kept because checking them passed a limit or raised an error
        # (facts, why), for the agent to warn about (take_unchecked()).
        self._unchecked: list[tuple[list[Term], str]] = []
        super().__init__(*args, **kwargs)

    def adopt(self, formula: ast.PrologText | str,
              bindings: Mapping[str, Term] | None = None) -> bool:
        """Adds the conjunction as one goal; False when already believed or already a goal.
        Checking whether it is believed is bounded by --max-inferences; one that passes a
        limit or raises an error adopts the goal (see :meth:`take_unchecked`)."""
        term = self._term(formula, bindings)
        seed = self._engine.pending_seed  # given by Prolog if the check runs agent code
        _, _, _, _, result, seeded = self._call(
            "adopt_checked", self._b, self._g, term, Atom("none") if seed is None else seed,
            None, None)
        if seeded == TRUE:
            self._engine.pending_seed = None
        if isinstance(result, Struct):  # unchecked(Message)
            self._unchecked.append((_conjuncts(term), str(result.args[0])))
            return True
        return result == "adopted"

    def take_unchecked(self) -> list[tuple[list[Term], str]]:
        """The goals adopted or kept since the last call because checking whether they are
        believed passed a limit or raised an error: (their facts, what the check met)."""
        unchecked, self._unchecked = self._unchecked, []
        return unchecked

    def drop(self, formula: ast.PrologText | str,
             bindings: Mapping[str, Term] | None = None) -> list[list[Term]]:
        """Removes every goal (of the top goal base) from which the formula follows."""
        term = self._term(formula, bindings)
        removed = self._call("drop", self._b, self._g, term, None)[3]
        assert isinstance(removed, list)
        return removed

    @property
    def goals_unchecked(self) -> bool:
        """Goals may have been achieved since the last :meth:`blind_commitment`."""
        return self._recheck or bool(self._achieved)

    def blind_commitment(self) -> list[list[Term]]:
        """Removes every goal whose facts are all believed (all goal bases); returns them,
        with those already removed by insert/delete since the last call. Prolog is asked
        only when percepts, messages or goal bases changed since (updates check themselves)."""
        if not self._recheck and not self._achieved:
            return []
        removed, self._achieved = self._achieved, []
        if self._recheck:
            result = self._call("check_goals_bounded", self._b, self._g, None, None)
            removed += result[2]
            self._unchecked += [(facts, str(why)) for facts, why in
                                (pair.args for pair in result[3])]  # type: ignore[union-attr]
            self._recheck = False
        unique: list[list[Term]] = []
        for goal in removed:
            if goal not in unique:
                unique.append(goal)
        return unique

    def goals(self) -> list[list[Term]]:
        """The top goal base; each goal is the list of its facts."""
        goals = self._call("goals", self._g, None)[1]
        assert isinstance(goals, list)
        return goals

    def goal_count(self) -> int:
        """How many goals the top goal base holds, none converted (a summary needs no more)."""
        return int(self._call("goal_count", self._g, None)[1])

    def push_goal_base(self, goals: Iterable[Iterable[Term]] = ()) -> None:
        """Starts a new top goal base (module focus) holding ``goals`` (lists of facts)."""
        self._call("push", self._b, self._g, [list(goal) for goal in goals])
        self._recheck = True

    def pop_goal_base(self) -> list[list[Term]]:
        """Removes the top goal base and returns its goals."""
        goals = self._call("pop", self._g, None)[1]
        assert isinstance(goals, list)
        return goals


def _conjuncts(term: Term) -> list[Term]:
    """The facts of a conjunction ``(a, b, c)`` (``true`` left out)."""
    if isinstance(term, Struct) and term.name == "," and len(term.args) == 2:
        return _conjuncts(term.args[0]) + _conjuncts(term.args[1])
    return [] if term == "true" else [term]
