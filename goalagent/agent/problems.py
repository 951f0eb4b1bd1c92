"""Every warning an agent gives while it runs, worded in one place: problems the
interpreter meets (Prolog errors in conditions, actions and preconditions, actions not
closed) and those of the environment and messaging seams. The agent goes on after each."""

from __future__ import annotations

import os
import traceback
from typing import TYPE_CHECKING

from goalagent import ast
from goalagent.events import ProblemKind
from goalagent.kb.interpreter_requests import Problem
from goalagent.kb.terms import Struct, Term, format_term

if TYPE_CHECKING:
    from goalagent.kb.mentalstate import MentalState


def warning_text(problem: Problem, program: ast.AgentProgram) -> str:
    """The warning for ``problem`` (the agent prefixes ``warning: agent NAME:``)."""
    kind, detail = problem.kind, problem.detail
    if kind is ProblemKind.CONDITION_ERROR:
        assert problem.rule is not None
        return (f"module {problem.rule.shown}, rule at {problem.rule.rule.pos}: Prolog error "
                f"in the condition: {detail}; the rule is not applicable")
    if kind is ProblemKind.PROLOG_WARNING:
        assert problem.rule is not None
        return (f"module {problem.rule.shown}, rule at {problem.rule.rule.pos}: SWI-Prolog "
                f"warning: {detail}")
    if kind is ProblemKind.LIMIT_EXCEEDED:
        assert problem.rule is not None
        return (f"module {problem.rule.shown}, rule at {problem.rule.rule.pos}: ran "
                f"{detail}; the rule is not applicable")
    if kind is ProblemKind.GOAL_UNCHECKED:
        assert problem.rule is not None
        return (f"module {problem.rule.module}, rule at {problem.rule.rule.pos}: checking "
                f"whether goal {goal_text(problem.term)} is achieved {detail}; the goal is kept")
    if kind is ProblemKind.PRECONDITION_ERROR:
        assert problem.spec_index is not None
        spec = program.actionspecs[problem.spec_index]
        return (f"precondition of {spec.name} at {spec.pos}: Prolog error: {detail}; the "
                "action is not enabled")
    if kind is ProblemKind.PERCEPTS_UNAVAILABLE:
        return f"could not get percepts: {detail}"
    assert problem.firing is not None and problem.action_index is not None
    action = problem.firing.rule.rule.actions[problem.action_index]
    if kind is ProblemKind.ACTION_NOT_CLOSED:
        return (f"{action.pos}: action {format_term(problem.term)} is not closed after its "
                "precondition; not performed")
    if kind is ProblemKind.ENVIRONMENT_REFUSED:
        return (f"{action.pos}: the environment could not perform "
                f"{format_term(problem.term)}: {detail}")
    if kind is ProblemKind.RECEIVER_UNBOUND:
        return f"{action.pos}: the receiver of {detail} is not bound; not sent"
    if kind is ProblemKind.DELIVERY_FAILED:
        return f"{action.pos}: {detail}"
    return f"{action.pos}: {action.name} failed: {detail}"


DEBUG_VARIABLE = "GOALAGENT_DEBUG"
"""Set (to anything but empty) to see tracebacks: of an internal error (the command line) and
of an exception raised in an environment's own Python code (below)."""


def cause_traceback(error: BaseException) -> str | None:
    """With ``GOALAGENT_DEBUG`` set, the traceback of the exception at the root of ``error``
    (an environment's own code that raised, behind the failure it was reported as), to find
    the bug in that code; None otherwise, or when nothing is behind ``error``."""
    if not os.environ.get(DEBUG_VARIABLE):
        return None
    root = error
    while root.__cause__ is not None:
        root = root.__cause__
    if root is error:
        return None
    return "".join(traceback.format_exception(type(root), root, root.__traceback__)).rstrip()
def goal_text(facts: Term | None) -> str:
    """A goal's facts as the program would write them (``on(a, b), clear(c)``)."""
    items = facts if isinstance(facts, list) else [facts]
    return ", ".join(format_term(fact) for fact in items)


def module_of(program: ast.AgentProgram, goal: ast.PrologText) -> str:
    """The module whose goals section holds ``goal``."""
    return next((module.name for module in program.modules
                 if any(written is goal for written in module.goals)), "init")


def goal_origin(program: ast.AgentProgram, ms: MentalState, running: str,
                facts: list[Term]) -> str:
    """Where a goal was written, if it is one of the program's goals sections' (else the
    program's file and the ``running`` module), for a warning about it."""
    written = facts[0] if len(facts) == 1 else _conjunction(facts)
    for goal in program.goals:
        if ms.unify(goal, written) is not None:
            return f"module {module_of(program, goal)}, goal at {goal.pos}"
    return f"module {running}, {program.file}"


def _conjunction(facts: list[Term]) -> Term:
    """``(f1, f2, ...)`` of a goal's facts."""
    term = facts[-1]
    for fact in reversed(facts[:-1]):
        term = Struct(",", (fact, term))
    return term
