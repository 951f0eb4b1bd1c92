"""Immutable program objects for `.goal` and `.mas2g` files, each with its source position.

Prolog fragments (clauses, queries, postconditions, terms) are kept as ``PrologText``: the
exact source text, already checked by SWI-Prolog's own reader, plus where it starts. The
mental state (``goalagent.kb``) turns them into Prolog goals; nothing here talks to Prolog.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from typing import Literal as TypingLiteral


@dataclass(frozen=True)
class Pos:
    """A source position: file, 1-based line and column, 0-based character offset."""

    file: str
    line: int
    col: int
    offset: int = 0

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"


@dataclass(frozen=True)
class PrologText:
    """A Prolog fragment exactly as written: a clause (no final dot), a query or a term."""

    text: str
    pos: Pos
    variables: tuple[str, ...] = ()  # named variables in order of first appearance

    def __str__(self) -> str:
        return self.text


MentalOp = TypingLiteral["bel", "goal", "a-goal", "goal-a", "percept", "true"]


@dataclass(frozen=True)
class MentalLiteral:
    """``bel(φ)``, ``goal(φ)``, ``a-goal(φ)``, ``goal-a(φ)``, ``percept(φ)`` or ``true``."""

    op: MentalOp
    query: PrologText | None
    pos: Pos


@dataclass(frozen=True)
class NotLiteral:
    """``not(L)``: negation as failure of a mental literal (or of a conjunction of them)."""

    condition: tuple[Literal, ...]
    pos: Pos


Literal = MentalLiteral | NotLiteral
Condition = tuple[Literal, ...]


@dataclass(frozen=True)
class Macro:
    """``#define name(Args) MSC.``: ``name(...)`` in a later condition expands to the MSC."""

    name: str
    params: tuple[str, ...]  # parameter variable names
    condition: Condition
    pos: Pos


BUILTIN_ACTIONS = frozenset(
    {"insert", "delete", "adopt", "drop", "print", "log", "exit-module", "send", "sendonce"}
)

Mood = TypingLiteral[":", "!", "?"]


@dataclass(frozen=True)
class ActionCall:
    """One action in a rule: a built-in, a user action (actionspec) or a user module call.
    ``overrides_builtin`` is set when an ``@env`` actionspec takes a built-in's name (the
    garbage environment's ``drop(ball)``), so the call goes to that actionspec."""

    name: str
    args: tuple[PrologText, ...]
    pos: Pos
    overrides_builtin: bool = False

    @property
    def arity(self) -> int:
        return len(self.args)

    @property
    def builtin(self) -> bool:
        return self.name in BUILTIN_ACTIONS and not self.overrides_builtin


@dataclass(frozen=True)
class SendAction:
    """``Receiver.send(MoodContent)`` / ``sendonce``; receiver is an agent name, a variable,
    ``allother`` or ``all``."""

    once: bool
    receiver: PrologText
    mood: Mood
    content: PrologText
    pos: Pos

    @property
    def name(self) -> str:
        return "sendonce" if self.once else "send"


Action = ActionCall | SendAction


@dataclass(frozen=True)
class Rule:
    """``if C then A.``, ``forall C do A.`` or ``listall V <- C do A.``; ``A`` is either an
    action combo (``actions``) or a nested block of rules (``rules``)."""

    kind: TypingLiteral["if", "forall", "listall"]
    condition: Condition
    pos: Pos
    actions: tuple[Action, ...] = ()
    rules: tuple[Rule, ...] | None = None
    list_var: str | None = None


@dataclass(frozen=True)
class ActionSpec:
    """A user action: ``name(Params) { pre{..} post{..} }``, internal when ``@int``."""

    name: str
    params: tuple[PrologText, ...]
    pre: PrologText
    post: PrologText
    pos: Pos
    internal: bool = False
    environment: bool = False  # marked @env (the default, but needed to reuse a built-in name)

    @property
    def arity(self) -> int:
        return len(self.params)


ExitOption = TypingLiteral["always", "never", "nogoals", "noaction"]
FocusOption = TypingLiteral["none", "new", "select", "filter"]
OrderOption = TypingLiteral["linear", "linearall", "random", "randomall"]


@dataclass(frozen=True)
class Module:
    """A module: ``init``, ``main``, ``event`` or a user module ``name(Params)``."""

    name: str
    kind: TypingLiteral["init", "main", "event", "user"]
    pos: Pos
    params: tuple[PrologText, ...] = ()
    exit: ExitOption | None = None  # None: the kind's default
    focus: FocusOption | None = None
    order: OrderOption | None = None
    rules: tuple[Rule, ...] = ()
    knowledge: tuple[PrologText, ...] = ()
    beliefs: tuple[PrologText, ...] = ()
    goals: tuple[PrologText, ...] = ()
    actionspecs: tuple[ActionSpec, ...] = ()

    @property
    def arity(self) -> int:
        return len(self.params)


@dataclass(frozen=True)
class AgentProgram:
    """A parsed `.goal` file. Knowledge, beliefs, goals and actionspecs are gathered from
    every module (they are global to the agent); ``modules`` keeps where they were written."""

    name: str
    file: str
    modules: tuple[Module, ...]
    macros: tuple[Macro, ...] = ()
    knowledge: tuple[PrologText, ...] = ()
    beliefs: tuple[PrologText, ...] = ()
    goals: tuple[PrologText, ...] = ()
    actionspecs: tuple[ActionSpec, ...] = ()
    warnings: tuple[str, ...] = field(default=(), compare=False)

    def module(self, name: str) -> Module | None:
        """The module called ``name`` (``init``, ``main``, ``event`` or a user module)."""
        for module in self.modules:
            if module.name == name:
                return module
        return None


@dataclass(frozen=True)
class AgentFile:
    """``"file.goal" [name = x, number = 3].`` in a `.mas2g` ``agentfiles`` section."""

    path: str
    name: str
    pos: Pos
    number: int = 1


@dataclass(frozen=True)
class LaunchRule:
    """``launch name : agentfile.`` or ``when [type=T, max=N]@env do launch name : file.``;
    a name ``*`` takes the entity's name."""

    agent_name: str
    agentfile: str
    pos: Pos
    on_entity: bool = False
    entity_type: str | None = None
    max: int | None = None
    number: int = 1


@dataclass(frozen=True)
class MasProgram:
    """A parsed `.mas2g` file."""

    file: str
    environment: str | None
    env_init: tuple[tuple[str, PrologText], ...]
    agentfiles: tuple[AgentFile, ...]
    launches: tuple[LaunchRule, ...]
    pos: Pos


def iter_rules(rules: Iterable[Rule]) -> Iterator[Rule]:
    """Every rule, nested ones included, in source order."""
    for rule in rules:
        yield rule
        if rule.rules:
            yield from iter_rules(rule.rules)
