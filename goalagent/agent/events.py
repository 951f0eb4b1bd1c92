"""Events an agent tells its listeners (``--trace``, the inspector): what the one rule
interpreter did, step by step, and what the cycle around it did. Each event carries its
data (rule position, bindings in the program's variable names, the term concerned) and a
line of text for people."""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Protocol

from goalagent import ast
from goalagent.agent.reports import describe, describe_firing
from goalagent.events import EventKind
from goalagent.kb.interpreter_requests import Step
from goalagent.kb.terms import Struct, Term, Var, format_term

_SHOWN_INSTANTIATIONS = 5  # a tried rule's line shows this many instantiations at most


Bindings = Mapping[str, Term]
"""Variable name (as the program writes it) -> its value: the one shape of bindings in the
Python API (``Event.bindings``, ``FiredRule.bindings``, an answer of ``Agent.query``)."""


@dataclass(frozen=True)
class Event:
    """One thing that happened in an agent, as ``Agent.listen`` tells it.

    Attributes:
        kind: what happened (a rule fired, a belief was added, ...).
        agent: the agent's name.
        text: one line for people, as ``--trace`` prints it.
        module: the rule's module (rule events and module calls), else None.
        pos: where the rule is written (rule events), else None.
        bindings: the variables of the firing (``RULE_FIRED``) or of the refused action
            (``ACTION_REFUSED``) with their values, e.g. ``event.bindings["X"]``; empty for
            other kinds (a tried rule has several: see ``instantiations``).
        instantiations: every instantiation of a tried rule's condition (``RULE_TRIED``), in
            the order they were tried; the one of a firing or refused action; else empty.
        term: the percept list, belief, goal (its facts) or message content concerned.
        actions: the actions a firing performed (``RULE_FIRED``), as its text shows them.
        cycle: the agent's cycle (set when the agent tells the event).
    """

    kind: EventKind
    agent: str
    text: str
    module: str | None = None
    pos: ast.Pos | None = None
    bindings: Bindings = field(default_factory=dict)
    instantiations: tuple[Bindings, ...] = ()
    term: Term | None = None
    actions: tuple[str, ...] = ()
    cycle: int = 0


Listener = Callable[[Event], None]


class Tracer(Protocol):
    """Receives trace events (``--trace``) as one line each: the agent, the kind of event
    (formats as its name, e.g. ``fired``) and the text."""

    def __call__(self, agent: str, kind: EventKind, text: str) -> None: ...


_MACRO_SUFFIX = re.compile(r"_M\d+$")  # a macro's own variable, renamed where it is used


def _shown(bindings: dict[str, Term]) -> str:
    """``X=a, T=[c]``: a macro's variables under the names its definition gives them
    (``T``, not ``T_M1``) unless the rule has one of that name too."""
    names = set(bindings)

    def display(name: str) -> str:
        plain = _MACRO_SUFFIX.sub("", name)
        return plain if plain not in names else name

    return ", ".join(f"{display(name)}={format_term(value)}" for name, value in bindings.items())


def _goal_text(goal: Term) -> str:
    """A goal (its facts as a list, or a conjunction) as text."""
    if isinstance(goal, list):
        return ", ".join(format_term(fact) for fact in goal)
    return format_term(goal)


def interpreter_event(agent: str, step: Step, program: ast.AgentProgram) -> Event:
    """The event for a step the interpreter told."""
    kind, rule = step.kind, step.rule
    performed: tuple[str, ...] = ()  # a firing's actions
    module = rule.module if rule is not None else None
    shown = rule.shown if rule is not None else None  # the name the user gave the module
    pos = rule.rule.pos if rule is not None else None
    if kind is EventKind.RULE_TRIED:
        assert rule is not None
        count = len(step.bindings)
        text = f"{shown} {pos}: {count} instantiation(s)"
        named = [f"[{_shown(b)}]" for b in step.bindings[:_SHOWN_INSTANTIATIONS] if b]
        if named:
            more = " ..." if count > _SHOWN_INSTANTIATIONS else ""
            text += ": " + " ".join(named) + more
    elif kind is EventKind.RULE_FIRED:
        assert rule is not None
        bindings = step.bindings[0]
        actions = describe_firing(rule, bindings, step.done, step.terms)
        performed = actions
        text = f"{shown} {pos} [{_shown(bindings)}] -> {' + '.join(actions) or '(block)'}"
    elif kind is EventKind.ACTION_REFUSED:
        assert rule is not None and step.action_index is not None
        action = rule.rule.actions[step.action_index]
        why = {"believed": "already believed", "exists": "already a goal",
               "precondition": "no precondition holds"}.get(step.reason, step.reason)
        text = f"{describe(action, step.bindings[0])} not enabled ({why}) at {action.pos}"
    elif kind is EventKind.PRECONDITION_FAILED:
        assert step.spec_index is not None
        spec = program.actionspecs[step.spec_index]
        assert step.term is not None
        text = f"{format_term(step.term)}: pre {{{spec.pre.text}}} does not hold"
    elif kind in (EventKind.BELIEF_ADDED, EventKind.BELIEF_DELETED):
        assert step.term is not None
        text = format_term(step.term)
    else:  # a goal adopted, dropped or achieved
        assert step.term is not None
        text = _goal_text(step.term)
    chosen = step.bindings[0] if kind is not EventKind.RULE_TRIED and step.bindings else {}
    return Event(kind, agent, text, module, pos, chosen, tuple(step.bindings), step.term,
                 performed)


def percepts_event(agent: str, percepts: Sequence[Term]) -> Event:
    return Event(EventKind.PERCEPTS, agent, ", ".join(format_term(p) for p in percepts),
                 term=list(percepts))


def message_event(agent: str, sender: str, mood: str, content: Term) -> Event:
    return Event(EventKind.MESSAGE_RECEIVED, agent, f"{sender}: {mood}{format_term(content)}",
                 term=content)


def module_event(agent: str, kind: EventKind, module: ast.Module, description: str) -> Event:
    """Entering (``description``: the call) or leaving a module."""
    return Event(kind, agent, f"module {description}", module.name, module.pos)


def goal_event(agent: str, kind: EventKind, goal: list[Term]) -> Event:
    """A goal (its facts) adopted, dropped or achieved."""
    return Event(kind, agent, _goal_text(goal), term=goal)


def anonymous(term: Term) -> Term:
    """``term`` with Prolog's fresh variables (``_G123``) as ``_``: their numbers mean
    nothing to the reader and differ from run to run."""
    if isinstance(term, Var):
        return Var("_") if term.name.startswith("_") else term
    if isinstance(term, list):
        return [anonymous(item) for item in term]
    if isinstance(term, Struct):
        return Struct(term.name, tuple(anonymous(arg) for arg in term.args))
    return term


def show_term(term: Term) -> str:
    """A term as people read it in traces and the inspector: fresh variables as ``_``."""
    return format_term(anonymous(term))


def _fresh_names(term: Term | None) -> Iterable[str]:
    if isinstance(term, Var) and term.name.startswith("_") and term.name != "_":
        yield term.name
    elif isinstance(term, list):
        for item in term:
            yield from _fresh_names(item)
    elif isinstance(term, Struct):
        for arg in term.args:
            yield from _fresh_names(arg)


def readable(event: Event) -> Event:
    """The event with the fresh variable names of its bindings and term (a message's
    ``?canMake(_G31,_G32)``, a firing's ``Y=f(_G7)``) shown as ``_`` in its text and in its
    actions."""
    names = {name for bindings in event.instantiations for value in bindings.values()
             for name in _fresh_names(value)}
    names.update(_fresh_names(event.term))
    if not names:
        return event
    ordered = sorted(names, key=len, reverse=True)  # _G123 before _G12

    def shown(text: str) -> str:
        for name in ordered:
            text = text.replace(name, "_")
        return text

    return replace(event, text=shown(event.text),
                               actions=tuple(shown(action) for action in event.actions))


_PROLOG_VARIABLE = re.compile(r"(?<![\w'])_G?\d+\b")  # _123 or _G123, not in an atom


def plain_variables(text: str) -> str:
    """Prolog's own variable names in a message (``f(_1204)``, ``handled(_G7)``) as ``_``,
    or ``_G1``, ``_G2``... (numbered in this message) for one that occurs more than once:
    their numbers change every cycle, so a warning repeated each cycle would not read as
    the same warning, and they mean nothing to the reader."""
    found = _PROLOG_VARIABLE.findall(text)
    shared = [name for name in dict.fromkeys(found) if found.count(name) > 1]
    names = {name: f"_G{number}" for number, name in enumerate(shared, 1)}
    return _PROLOG_VARIABLE.sub(lambda match: names.get(match.group(0), "_"), text)
