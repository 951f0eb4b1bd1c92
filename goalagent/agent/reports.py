"""What a cycle did, for tests, traces and the CLI: the rules that fired with their bindings
and actions, the actions in order, percepts, messages and warnings.

The interpreter keeps each call's firings in Prolog (a journal); a report holds spans of
those journals and builds its entries only when read, so a cycle nobody asks about costs
no conversion. A module call splits the spans of its caller's journal: the called
module's firings and actions come where the call happened.
"""

from __future__ import annotations

from dataclasses import dataclass

from goalagent import ast
from goalagent.kb.interpreter import JournalEntry, RunOutcome
from goalagent.kb.prolog_modules import instantiate
from goalagent.kb.rule_registry import RuleInfo
from goalagent.kb.terms import Struct, Term, format_term
from goalagent.parser import rename_variables

Bindings = dict[str, Term]


def describe(action: ast.Action, bindings: Bindings, term: Term | None = None) -> str:
    """An action as performed with ``bindings`` (``insert(cycle(2))``); ``term`` is its
    closed form when only its precondition bound it."""
    if term is not None:
        return format_term(term)
    if isinstance(action, ast.SendAction):
        receiver = instantiate(action.receiver, bindings)
        content = instantiate(action.content, bindings)
        return f"{format_term(receiver)}.{action.name}({action.mood}{format_term(content)})"
    if not action.args:
        return action.name
    if not action.builtin:  # a user action or a module call
        args = tuple(instantiate(arg, bindings) for arg in action.args)
        return format_term(Struct(action.name, args))
    values = {name: format_term(value) for name, value in bindings.items()}
    shown = ", ".join(rename_variables(arg.text, values) for arg in action.args)
    return f"{action.name}({shown})"


def describe_firing(rule: RuleInfo, bindings: Bindings, done: int,
                    terms: tuple[Term, ...]) -> tuple[str, ...]:
    """The actions a firing performed (its first ``done``), described."""
    recorded = iter(terms)
    return tuple(describe(action, bindings, next(recorded) if index in rule.recorded else None)
                 for index, action in enumerate(rule.rule.actions[:done]))


class FiredRule:
    """A rule that fired: where it is, with which bindings, and the actions it performed."""

    __slots__ = ("_entry", "_bindings", "_actions")

    def __init__(self, entry: JournalEntry) -> None:
        self._entry = entry
        self._bindings: Bindings | None = None
        self._actions: tuple[str, ...] | None = None

    def __repr__(self) -> str:
        return (f"FiredRule(module={self.module!r}, pos={self.pos!r}, "
                f"bindings={self.bindings!r}, actions={self.actions!r})")

    @property
    def module(self) -> str:
        """The name of the rule's module."""
        return self._entry.rule.module

    @property
    def shown(self) -> str:
        """The module's name as its file gives it (a GOAL 6 main module: its own name)."""
        return self._entry.rule.shown

    @property
    def pos(self) -> ast.Pos:
        """Where the rule is written."""
        return self._entry.rule.rule.pos

    @property
    def line(self) -> int:
        return self.pos.line

    @property
    def bindings(self) -> Bindings:
        """The rule's variables (and those it was given) with their values."""
        if self._bindings is None:
            self._bindings = self._entry.bindings
        return self._bindings

    @property
    def actions(self) -> tuple[str, ...]:
        """The descriptions of the actions the rule performed, in order."""
        if self._actions is None:
            entry = self._entry
            self._actions = describe_firing(entry.rule, self.bindings, entry.done, entry.terms)
        return self._actions


class RunRecord:
    """One interpreter call: its outcome and journal (set when the call returns; None if
    it failed), read as fired rules and actions at most once; while it runs, where the
    report's next spans of it start (a module call splits them) and its module calls so
    far. As a span it is the whole call."""

    __slots__ = ("outcome", "entries_from", "actions_from", "module_calls", "_fired",
                 "_actions")
    start = 0
    stop = None

    def __init__(self) -> None:
        self.outcome: RunOutcome | None = None
        self.entries_from = 0
        self.actions_from = 0
        self.module_calls = 0
        self._fired: list[FiredRule] | None = None
        self._actions: list[str] | None = None

    @property
    def record(self) -> RunRecord:
        """As a span: the call itself."""
        return self

    def fired(self) -> list[FiredRule]:
        """The firings, in the order they completed."""
        if self._fired is None:
            entries = self.outcome.entries() if self.outcome is not None else []
            self._fired = [FiredRule(entry) for entry in entries]
        return self._fired

    def actions(self) -> list[str]:
        """The actions performed, in order."""
        if self._actions is None:
            self._actions = [action for fired in self.fired() for action in fired.actions]
        return self._actions


class Span:
    """Entries ``start`` to ``stop`` (None: to the end) of a call's firings or actions."""

    __slots__ = ("record", "start", "stop")

    def __init__(self, record: RunRecord, start: int = 0, stop: int | None = None) -> None:
        self.record = record
        self.start = start
        self.stop = stop


class CycleReport:
    """What happened in one cycle (for tests, traces and the CLI): ``percepts``,
    ``messages``, ``warnings``, and -- built when read -- ``fired`` and ``actions``."""

    __slots__ = ("cycle", "percepts", "messages", "warnings", "entries", "performed",
                 "action_count")

    def __init__(self, cycle: int) -> None:
        self.cycle = cycle
        self.percepts: list[Term] = []
        self.messages: list[tuple[str, str, Term]] = []
        self.warnings: list[str] = []
        # In the order they happened: spans of the interpreter calls' firings and actions
        # (a whole call is its RunRecord).
        self.entries: list[Span | RunRecord] = []
        self.performed: list[Span | RunRecord] = []
        self.action_count = 0  # actions and module calls

    def __repr__(self) -> str:
        return (f"CycleReport(cycle={self.cycle}, percepts={self.percepts!r}, "
                f"messages={self.messages!r}, warnings={self.warnings!r})")

    @property
    def fired(self) -> list[FiredRule]:
        """The rules that fired in the cycle, in order."""
        return [fired for span in self.entries
                for fired in span.record.fired()[span.start:span.stop]]

    @property
    def actions(self) -> list[str]:
        """The descriptions of the actions performed in the cycle, in order."""
        return [action for span in self.performed
                for action in span.record.actions()[span.start:span.stop]]

    @property
    def acted(self) -> bool:
        """Some action (or module call) was performed."""
        return self.action_count > 0


@dataclass(frozen=True)
class RunResult:
    """The outcome of ``Agent.run``."""

    cycles: int
    terminated: bool
    actions: int
    goals_left: list[list[Term]]
