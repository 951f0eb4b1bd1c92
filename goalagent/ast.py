"""Immutable program objects for GOAL's files, each with its source position: one agent
program (``AgentProgram``) whether it was written in the single-file format (`.goal`) or in
GOAL 6's multi-file format (`.mod2g` modules, `.act2g` action specifications and `.pl` files
named by an agent definition of a `.mas2g`), the `.mas2g` system, and `.test2g` tests.

Prolog fragments (clauses, queries, postconditions, terms) are kept as ``PrologText``: the
exact source text, already checked by SWI-Prolog's own reader, plus where it starts. The
mental state (``goalagent.kb``) turns them into Prolog goals; nothing here talks to Prolog.
"""

from __future__ import annotations

import re
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


MentalOp = TypingLiteral["bel", "goal", "a-goal", "goal-a", "percept", "true", "done"]


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


def macro_local(name: str, expansion: int) -> str:
    """The name a macro's own variable (not a parameter) takes in the macro's
    ``expansion``-th use, so that uses do not share it."""
    return f"{name}_M{expansion}"


def is_macro_local(name: str) -> bool:
    """True for a variable a macro expansion made (see ``macro_local``)."""
    return re.fullmatch(r"\w+_M\d+", name) is not None


@dataclass(frozen=True)
class Macro:
    """``#define name(Args) MSC.``: ``name(...)`` in a later condition expands to the MSC."""

    name: str
    params: tuple[str, ...]  # parameter variable names
    condition: Condition
    pos: Pos


# GOAL 7's timer and channel actions (goalagent.agent.timers)
GOAL7_ACTIONS = frozenset({"starttimer", "canceltimer", "subscribe", "unsubscribe"})
BUILTIN_ACTIONS = frozenset(
    {"insert", "delete", "adopt", "drop", "print", "log", "exit-module", "send", "sendonce",
     "sleep"}
) | GOAL7_ACTIONS

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
    """A module: ``init``, ``main``, ``event`` or a user module ``name(Params)``. A module
    file (`.mod2g`) used as an agent's init, main or event module is named after that role;
    ``declared`` keeps the name its file gives it."""

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
    declared: str | None = None
    has_program: bool = True  # False: written without a program section

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
    # GOAL 6+ (an agent definition's module files) keeps a received message for the one
    # cycle after it arrives (its MentalState: "a message base is cleared after every
    # decision cycle"); GOAL 4/5 .goal files keep received/2 until the agent deletes it.
    messages_for_one_cycle: bool = False

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
    limits: tuple[tuple[str, object], ...] = ()  # e.g. (("sandbox", True),): see kb.limits


@dataclass(frozen=True)
class UseClause:
    """``use ref as case.`` (or ``use ref.``, or the newest dialect's ``use ref for
    decisions.``) of GOAL 6+: the file ``ref`` names (a dotted path or a quoted file name,
    as written) and how it is used (None when the clause does not say)."""

    ref: str
    case: str | None
    pos: Pos
    quoted: bool = False


@dataclass(frozen=True)
class PerceptRule:
    """The newest dialect's percept handling in an agent definition: ``add p/1.`` (percepts
    of p/1 become beliefs), ``replace p/1.`` (the beliefs of p/1 are the current percepts)
    or ``update p/1.`` (replaced when the environment sends p/1 percepts)."""

    how: TypingLiteral["add", "replace", "update"]
    name: str
    arity: int
    pos: Pos


@dataclass(frozen=True)
class AgentDefinition:
    """``define name as agent { use m as main module. ... }`` in a GOAL 6+ `.mas2g`: the
    module files of the agent's roles (init, main, event) and, in the newest dialect, its
    percept rules."""

    name: str
    pos: Pos
    uses: tuple[UseClause, ...]
    percept_rules: tuple[PerceptRule, ...] = ()


@dataclass(frozen=True)
class LaunchRule:
    """``launch name : agentfile.``, ``when [type=T, max=N]@env do launch name : file.``
    (GOAL 4/5) or ``launch a with name = n, number = 2.``, ``when type = T launch a with
    max = N.`` (GOAL 6+); a name ``*`` takes the entity's name. Instructions of one
    ``when`` rule share ``group``: they are launched together on one entity."""

    agent_name: str
    agentfile: str
    pos: Pos
    on_entity: bool = False
    entity_type: str | None = None
    max: int | None = None
    number: int = 1
    entity_name: str | None = None
    group: int = 0


@dataclass(frozen=True)
class MasProgram:
    """A parsed `.mas2g` file: the environment (a registered name, ``module:Class`` or a
    GOAL jar file name) with its init parameters, the agents (GOAL 4/5 agent files or GOAL
    6+ agent definitions) and the launch policy."""

    file: str
    environment: str | None
    env_init: tuple[tuple[str, PrologText], ...]
    agentfiles: tuple[AgentFile, ...]
    launches: tuple[LaunchRule, ...]
    pos: Pos
    definitions: tuple[AgentDefinition, ...] = ()
    env_pos: Pos | None = None
    warnings: tuple[str, ...] = field(default=(), compare=False)  # GOAL's MAS warnings


def iter_rules(rules: Iterable[Rule]) -> Iterator[Rule]:
    """Every rule, nested ones included, in source order."""
    for rule in rules:
        yield rule
        if rule.rules:
            yield from iter_rules(rule.rules)


# ----------------------------------------------------------------------------- tests


@dataclass(frozen=True)
class TestCondition:
    """A temporal test condition over the states an agent passes through: ``eventually
    C``, ``always C``, ``never C``, ``atend C`` (the last state) or ``C leadsto D`` (after
    a state where C holds, D holds in that one or a later one). ``text`` as written."""

    kind: TypingLiteral["eventually", "always", "never", "atend", "leadsto", "atstart",
                        "watch"]
    condition: Condition
    pos: Pos
    text: str
    then: Condition | None = None


@dataclass(frozen=True)
class ModuleTest:
    """``test m with pre{C} in{conditions} post{D}``: while module ``m`` runs, C holds
    when it starts, the conditions hold over its run, D holds when it ends."""

    module: str
    pos: Pos
    pre: Condition | None = None
    conditions: tuple[TestCondition, ...] = ()
    post: Condition | None = None


@dataclass(frozen=True)
class TestStep:
    """What a test makes an agent do: ``do a [until C].`` (run a module or perform an
    action, the main module until C holds or the agent stops), GOAL 5's ``assert C.`` and
    ``evaluate { conditions } in do a [until C].``."""

    kind: TypingLiteral["do", "assert", "evaluate"]
    pos: Pos
    target: str = ""
    action: Action | None = None
    until: Condition | None = None
    condition: Condition | None = None
    conditions: tuple[TestCondition, ...] = ()
    message: str | None = None
    actions: tuple[Action, ...] = ()  # do a + b: every action of the step


@dataclass(frozen=True)
class AgentTest:
    """The steps a test makes the agent called ``agent`` take."""

    agent: str
    pos: Pos
    steps: tuple[TestStep, ...]


@dataclass(frozen=True)
class TestProgram:
    """A parsed `.test2g` file: the system it runs (a `.mas2g`), a time limit in seconds,
    the module tests and the agents' steps."""

    file: str
    mas: str
    mas_pos: Pos
    timeout: float | None
    module_tests: tuple[ModuleTest, ...]
    agent_tests: tuple[AgentTest, ...]
