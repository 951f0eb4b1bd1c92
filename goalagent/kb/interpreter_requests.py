"""What the rule interpreter (rules.pl) asks of Python while it runs an agent's rules, and
what it tells: requests decoded from Prolog terms into typed values and answered by the
agent's :class:`Requests`.

Prolog asks Python (``'$ga_py'/2``) for what only Python can do -- environment actions,
print/log, messages, module calls, the agent's random rule order -- and tells it problems
(warnings) and, when someone listens, every step (events). The Prolog term shapes stay
here, inside ``goalagent.kb``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from goalagent.events import EventKind, ProblemKind
from goalagent.kb.calls import define_foreign
from goalagent.kb.engine import Engine, KBError
from goalagent.kb.limits import limit_text
from goalagent.kb.rule_registry import RULES, RuleInfo
from goalagent.kb.terms import Atom, Struct, Term, format_term

__all__ = ["Answerer", "Firing", "MOODS", "Problem", "Requests", "Step", "answering",
           "define_requests"]

_TRUE, _FALSE = Atom("true"), Atom("false")
MOODS = {":": "indicative", "!": "imperative", "?": "interrogative"}
"""A message's mood sign and the name rules.pl gives it."""
_MOOD_SIGNS = {name: sign for sign, name in MOODS.items()}


@dataclass(frozen=True)
class Firing:
    """One instantiation of a rule: the rule and the values of its bindings."""

    rule: RuleInfo
    values: tuple[Term, ...]

    @property
    def bindings(self) -> dict[str, Term]:
        """The bindings by variable name."""
        return dict(zip(self.rule.names, self.values, strict=False))


@dataclass(frozen=True)
class Problem:
    """A problem met running rules (the agent words and warns it): ``firing`` and
    ``action_index`` locate an action, ``rule`` a condition, ``spec_index`` an actionspec;
    ``detail`` is the error's message, ``term`` the action concerned."""

    kind: ProblemKind
    detail: Term = ""
    firing: Firing | None = None
    action_index: int | None = None
    rule: RuleInfo | None = None
    spec_index: int | None = None
    term: Term | None = None  # the action concerned


@dataclass(frozen=True)
class Step:
    """One step of the interpreter, told only when the agent has listeners. ``bindings``:
    per instantiation (RULE_TRIED) or the firing's (others); ``term``: the belief, goal or
    action concerned; ``reason``: why an action was refused."""

    kind: EventKind
    rule: RuleInfo | None = None
    bindings: tuple[dict[str, Term], ...] = ()
    done: int = 0
    terms: tuple[Term, ...] = ()
    action_index: int | None = None
    spec_index: int | None = None
    term: Term | None = None
    reason: str = ""


class Requests(Protocol):
    """What the interpreter asks of the agent while it runs the agent's rules."""

    def shuffle(self, count: int) -> list[int]:
        """A random order of ``count`` rules (the indices 0 .. count - 1)."""

    def output(self, text: str, log: bool) -> None:
        """``print/1`` (or ``log/1`` when ``log``) of ``text``."""

    def act(self, firing: Firing, index: int, action: Term) -> bool:
        """Send a closed user action to the environment; False when it refused."""

    def send(self, firing: Firing, index: int, once: bool, mood: str, receiver: Term,
             content: Term) -> bool:
        """A message (``mood`` ``:``, ``!`` or ``?``); False when not sent (not enabled)."""

    def call_module(self, firing: Firing, index: int, module: int, args: list[Term],
                    entries: int, position: int) -> bool:
        """Run the program's module ``module`` with ``args``; False when its parameters do
        not match. ``entries`` firings and ``position`` actions precede this call in the
        running call's journal."""

    def goal7(self, name: str, args: list[Term]) -> None:
        """GOAL 7's starttimer, canceltimer, subscribe or unsubscribe with ``args``."""

    def problem(self, problem: Problem) -> None:
        """A warning."""

    def step(self, step: Step) -> None:
        """An event, when the agent has listeners."""



class Answerer:
    """Decodes the interpreter's requests for one :class:`Requests`."""

    def __init__(self, requests: Requests) -> None:
        self.requests = requests

    def __call__(self, request: Term) -> Term | None:
        assert isinstance(request, Struct)
        name, args = request.name, request.args
        requests = self.requests
        if name == "event":
            requests.step(_step(args[0]))  # type: ignore[arg-type]
            return None
        if name == "problem":
            requests.problem(_problem(args[0]))  # type: ignore[arg-type]
            return None
        if name == "shuffle":
            return requests.shuffle(int(args[0]))  # type: ignore[arg-type]
        if name in ("print", "log"):
            requests.output(str(args[0]), log=name == "log")
            return None
        if name == "act":
            done = requests.act(_firing(args[0]), int(args[1]), args[2])  # type: ignore
            return Atom("done" if done else "refused")
        if name == "send":
            firing, index, once, mood, receiver, content = args
            sent = requests.send(_firing(firing), int(index), once == "true",  # type: ignore
                                 _MOOD_SIGNS[str(mood)], receiver, content)
            return _TRUE if sent else _FALSE
        if name == "goal7":
            requests.goal7(str(args[0]), list(args[1]))  # type: ignore[arg-type]
            return None
        if name == "call":
            firing, index, module, call_args, entries, position = args
            called = requests.call_module(_firing(firing), int(index), int(module),  # type: ignore
                                          list(call_args), int(entries),  # type: ignore
                                          int(position))  # type: ignore[arg-type]
            return _TRUE if called else _FALSE
        raise KBError(f"internal: unknown request from the interpreter: {format_term(request)}")


answering: list[Answerer] = []
"""The answerers of the running interpreter calls, the innermost last."""


def _answer(request: Term) -> Term | None:
    """The foreign predicate '$ga_py'/2: the innermost running call's answerer replies."""
    if not answering:
        return None  # a mental-state call outside the interpreter has no one to tell
    return answering[-1](request)


def _firing(term: Term) -> Firing:
    """``f(RuleId, Values)`` as a :class:`Firing`."""
    rule_id, values = term.args  # type: ignore[union-attr]
    return Firing(RULES[int(rule_id)], tuple(values))  # type: ignore[arg-type]


def _problem(term: Struct) -> Problem:
    """A problem term of rules.pl (see problem/1)."""
    name, args = term.name, term.args
    if name == "condition":
        return Problem(ProblemKind.CONDITION_ERROR, args[1], rule=RULES[int(args[0])])
    if name == "warning":
        return Problem(ProblemKind.PROLOG_WARNING, args[1], rule=RULES[int(args[0])])
    if name == "precondition":
        return Problem(ProblemKind.PRECONDITION_ERROR, args[1], spec_index=int(args[0]))
    if name == "action":
        return Problem(ProblemKind.ACTION_ERROR, args[2], firing=_firing(args[0]),
                       action_index=int(args[1]))
    if name == "limit":
        return Problem(ProblemKind.LIMIT_EXCEEDED, limit_text(args[1]), rule=RULES[int(args[0])])
    if name == "goal_check":
        rule = RULES[int(args[0])] if isinstance(args[0], int) else None
        return Problem(ProblemKind.GOAL_UNCHECKED, args[2], rule=rule, term=args[1])
    return Problem(ProblemKind.ACTION_NOT_CLOSED, firing=_firing(args[0]),
                   action_index=int(args[1]), term=args[2])


_CHANGES = {
    ("belief", "added"): EventKind.BELIEF_ADDED,
    ("belief", "deleted"): EventKind.BELIEF_DELETED,
    ("goal", "adopted"): EventKind.GOAL_ADOPTED,
    ("goal", "dropped"): EventKind.GOAL_DROPPED,
    ("goal", "achieved"): EventKind.GOAL_ACHIEVED,
}


def _step(term: Struct) -> Step:
    """An event term of rules.pl (see tell/1)."""
    name, args = term.name, term.args
    if name == "tried":
        info = RULES[int(args[0])]
        return Step(EventKind.RULE_TRIED, info,
                    tuple(dict(zip(info.names, values, strict=False))
                          for values in args[1]))  # type: ignore[union-attr]
    if name == "fired":
        info = RULES[int(args[0])]
        return Step(EventKind.RULE_FIRED, info, (dict(zip(info.names, args[1],  # type: ignore
                                                          strict=False)),),
                    done=int(args[2]), terms=tuple(args[3]))  # type: ignore[arg-type]
    if name == "refused":
        firing = _firing(args[0])
        return Step(EventKind.ACTION_REFUSED, firing.rule, (firing.bindings,),
                    action_index=int(args[1]), reason=str(args[2]))  # type: ignore[arg-type]
    if name == "precondition_failed":
        return Step(EventKind.PRECONDITION_FAILED, spec_index=int(args[0]),  # type: ignore
                    term=args[1])
    return Step(_CHANGES[(name, str(args[0]))], term=args[1])


_answered: set[int] = set()  # engines (by id) whose '$ga_py'/2 is defined


def define_requests(engine: Engine) -> None:
    """Defines the interpreter's foreign predicate '$ga_py'/2 once per engine."""
    if id(engine) not in _answered:
        define_foreign(engine, "ga_kb", "$ga_py", _answer)
        _answered.add(id(engine))
