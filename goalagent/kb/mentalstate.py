"""The mental state of one agent on SWI-Prolog: its parts joined, and the entry of the rule
interpreter.

Each part owns one job on the agent's two Prolog modules (prolog_modules.py, the base):

- ``conditions.py``: conditions compiled into clauses and answered (queries, unification);
- ``beliefbase.py``: insert, delete, files of facts, the beliefs;
- ``goalbases.py``: the stack of goal bases, adopt, drop, blind commitment;
- ``percepts_and_mail.py``: the percept base and the mailbox;
- ``identity.py``: ``me/1`` and ``agent/1`` (:class:`AgentDirectory`).

A rule's whole condition is compiled once into a clause of the belief module and evaluated
in one Prolog call with the bindings passed in. The rules themselves run in the interpreter
(``goalagent.kb.interpreter``, rules.pl): :meth:`MentalState.run` is its one call a cycle.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from goalagent import ast
from goalagent.kb.beliefbase import BeliefBase
from goalagent.kb.conditions import Conditions
from goalagent.kb.engine import KBError, PrologRuntimeError
from goalagent.kb.goalbases import GoalBases
from goalagent.kb.identity import Identity
from goalagent.kb.limits import refused_precondition, stopping_error
from goalagent.kb.memory import check_held
from goalagent.kb.percepts_and_mail import PerceptsAndMail
from goalagent.kb.prolog_modules import FALSE, TRUE
from goalagent.kb.terms import Atom, Struct, Term, format_term

__all__ = ["MentalState", "PlanPredicate"]


class PlanPredicate:
    """A plan of module passes defined as a predicate of the agent's belief module
    (:meth:`MentalState.define_plan`), called with no input."""

    __slots__ = ("handle",)

    def __init__(self, handle: int) -> None:
        self.handle = handle


class MentalState(Conditions, BeliefBase, GoalBases, PerceptsAndMail, Identity):
    """Knowledge, beliefs, goal bases, percepts and mailbox of one agent (two Prolog modules)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._run_pred: int | None = None  # rules.pl's run/3, looked up on the first run
        self._plans = 0  # plans defined (define_plan)
        super().__init__(*args, **kwargs)

    def __enter__(self) -> MentalState:
        """``with MentalState(...) as state:`` closes the state at the end of the block."""
        return self

    def __exit__(self, *exc: Any) -> None:
        """Closes the state (frees its Prolog modules)."""
        self.close()

    def declare_actions(self, specs: Sequence[ast.ActionSpec]) -> None:
        """Makes the actionspecs known to the rule interpreter: each spec's precondition and
        postcondition, in program order (the first that applies wins; see rules.pl)."""
        items = []
        for index, spec in enumerate(specs):
            head = format_term(Atom(spec.name))
            if spec.params:
                head += "(" + ", ".join(param.text for param in spec.params) + ")"
            text = f"'$spec'({head}, ({spec.pre.text}\n), ({spec.post.text}\n))"
            items.append(Struct("spec", (index, TRUE if spec.internal else FALSE, text)))
        try:
            self._call("declare_actions", self._b, items)
        except PrologRuntimeError as error:
            raise refused_precondition(error, specs) from None

    def define_plan(self, plan: Term) -> PlanPredicate:
        """``plan`` (a term for run/3) as a predicate of the belief module, which
        :meth:`run` calls without putting the plan into the call each time."""
        name = f"$ga_plan{self._plans}"
        self._plans += 1
        self._call("define_plan", self._b, Atom(name), plan)
        return PlanPredicate(self._engine.own_predicate(name, 2, str(self._b)))

    def run(self, plan: Term | PlanPredicate) -> tuple[int, int]:
        """Runs a plan of module passes (a term, or defined by :meth:`define_plan`) in one
        call of the rule interpreter (run/3 in rules.pl; see goalagent.kb.interpreter):
        its outcome (one integer) and the handle of its journal, recorded in Prolog (the
        caller frees it: see ``Record``)."""
        if self._closed:
            raise KBError(f"the mental state of {self.agent_name} is closed")
        watch = self._watchdog
        watch.time_limit, watch.running = self.limits.max_query_seconds, self._memory
        try:
            if type(plan) is PlanPredicate:
                outcome, journal = self._engine.call_once(plan.handle, 2, (), 0, 1)
            else:
                if self._run_pred is None:
                    self._run_pred = self._engine.predicate("run", 3, "ga_kb")
                outcome, journal = self._engine.call_once(self._run_pred, 3, ((0, plan),), 1, 2)
        except PrologRuntimeError as error:
            raise stopping_error(error) from None
        if watch.generation != self._generation:  # a memory alarm since its last account
            self._generation = watch.generation
            check_held(self._engine, self._b, self.limits, self._generation)
        self._recheck = bool(outcome & 1)
        return outcome, journal
