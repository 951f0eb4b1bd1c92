"""The Python side of the one rule interpreter (``rules.pl``): a program's rules compiled
into Prolog and module passes run in one call.

Every rule becomes one clause shared by all agents that read it alike (its condition is
compiled in each agent's belief module), every list of rules (a module, a nested block) a
pass; :meth:`CompiledProgram.run` runs module passes in one Prolog call, answering what the
interpreter asks of Python with the agent's :class:`~goalagent.kb.interpreter_requests.Requests`
(interpreter_requests.py). Rules are known by their ids (rule_registry.py).
"""

from __future__ import annotations

import weakref
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from goalagent import ast
from goalagent.kb.conditions import CompiledCondition
from goalagent.kb.engine import Engine, KBError, Record
from goalagent.kb.interpreter_requests import (
    MOODS,
    Answerer,
    Requests,
    answering,
    define_requests,
)
from goalagent.kb.mentalstate import MentalState, PlanPredicate
from goalagent.kb.rule_registry import RULES, RuleInfo, register_rule
from goalagent.kb.terms import Atom, Struct, Term, format_term

__all__ = ["CompiledProgram", "JournalEntry", "ModuleCode", "RunOutcome", "listall_variables"]

_TRUE, _FALSE = Atom("true"), Atom("false")

# Clause names of compiled rules and passes, shared by all agents: key -> name.
_shared_clauses: dict[tuple, str] = {}
# Per program object (while it lives): its directives, its modules' compiled passes and the
# first agent's mental state, so that the agents launched from one program (bench/agents.py:
# 10,000) compile only their conditions, copied from that agent's.
_compiled_programs: dict[int, tuple[weakref.ref, str, dict[int, ModuleCode], weakref.ref]] = {}


def listall_variables(rule: ast.Rule, given: Sequence[str] = ()) -> tuple[str, ...]:
    """The variables whose values ``listall L <- C`` collects, as GOAL does: the free
    variables of C's positive literals (not under ``not``) in order of occurrence, without
    anonymous ones (``_X``), L itself, those ``given`` (a module's parameters, an enclosing
    rule's bindings) and a macro's own. L gets one entry per answer: the value of the one
    variable, or the list of their values when there are several."""
    names: list[str] = []
    for literal in rule.condition:
        if isinstance(literal, ast.MentalLiteral) and literal.query is not None:
            for name in literal.query.variables:
                if (name not in names and name != rule.list_var and not name.startswith("_")
                        and name not in given and not ast.is_macro_local(name)):
                    names.append(name)
    return tuple(names)


# ----------------------------------------------------------------------------- journal


@dataclass(frozen=True)
class JournalEntry:
    """A firing: its rule and bindings' values, how many of its actions were performed,
    and the closed forms of those of its user actions that only a precondition closes."""

    rule: RuleInfo
    values: tuple[Term, ...]
    done: int
    terms: tuple[Term, ...]

    @property
    def bindings(self) -> dict[str, Term]:
        return dict(zip(self.rule.names, self.values, strict=False))


class RunOutcome(Record):
    """What one :meth:`CompiledProgram.run` did: ``actions`` performed (all passes),
    ``last_actions`` of the last pass (when counted), whether the last pass ``exited``
    (exit-module), and its journal: the firings in the order they completed, kept in
    Prolog (this object is the journal's :class:`Record`) until someone reads them
    (:meth:`entries`): most cycles nobody does."""

    __slots__ = ("_outcome", "actions", "_entries")

    def __init__(self, outcome: int, engine: Engine, journal: int) -> None:
        Record.__init__(self, engine, journal)
        self._outcome = outcome
        self.actions = outcome >> 32
        self._entries: list[JournalEntry] | None = None

    @property
    def last_actions(self) -> int:
        return (self._outcome >> 2) & 0x3FFFFFFF

    @property
    def exited(self) -> bool:
        return bool(self._outcome & 2)

    def entries(self) -> list[JournalEntry]:
        """The journal's entries (converted once)."""
        if self._entries is None:
            self._entries = []
            for entry in self.value():  # type: ignore[union-attr]
                rule_id, bound, done, terms = entry.args
                values = bound.args if isinstance(bound, Struct) else ()  # (v/0: the atom v)
                self._entries.append(JournalEntry(RULES[int(rule_id)], values, int(done),
                                                  tuple(terms)))
        return self._entries


# ----------------------------------------------------------------------------- compiling


@dataclass(frozen=True)
class ModuleCode:
    """A module compiled into a pass: its clause and the names of its given variables
    (the module's parameters)."""

    module: ast.Module
    clause: Atom
    given: tuple[str, ...]


_DEFAULT_ORDER = {"init": "linearall", "event": "linearall", "main": "linear", "user": "linear"}


class CompiledProgram:
    """An agent program's rules compiled for one mental state (clauses shared with every
    agent that runs the same text)."""

    def __init__(self, state: MentalState, program: ast.AgentProgram) -> None:
        self._state = state
        self._engine: Engine = state.engine
        self._specs = {(spec.name, spec.arity) for spec in program.actionspecs}
        self._modules = {(m.name, m.arity): index for index, m in enumerate(program.modules)}
        self._directives = state.directives
        self._codes: dict[int, ModuleCode] = {}
        self._plans: dict[tuple, PlanPredicate] = {}  # plans defined in the agent's module
        self._answerer: Answerer | None = None
        define_requests(self._engine)
        state.declare_actions(program.actionspecs)
        compiled = _compiled_programs.get(id(program))
        if compiled is not None and compiled[0]() is program and compiled[1] == self._directives:
            self._codes = compiled[2]  # the rule and pass clauses exist: only the conditions
            like = compiled[3]()  # are this agent's own: copied from an earlier agent's
            if like is None or like.closed or like.limits != state.limits or self._directives:
                like = None  # (loaded alike: directives may make each agent's state its own)
                if not self._directives:  # the next agents copy this one's
                    _compiled_programs[id(program)] = (*compiled[:3], weakref.ref(state))
            rules = [rule for module in program.modules for rule in ast.iter_rules(module.rules)]
            if like is None or not state.copy_conditions(like, [r.condition for r in rules]):
                for rule in rules:
                    self._compile_condition(rule)
            return
        for module in program.modules:
            self._codes[id(module)] = self._compile_module(module)
        key = id(program)
        forget = lambda _: _compiled_programs.pop(key, None)  # noqa: E731 - when it dies
        _compiled_programs[key] = (weakref.ref(program, forget), self._directives, self._codes,
                                   weakref.ref(state))

    def add_module(self, module: ast.Module) -> None:
        """Compiles a module made outside the program (a test step's actions, run as a
        rule ``if true then A``): its rules may call the program's actions and modules."""
        if id(module) not in self._codes:
            self._codes[id(module)] = self._compile_module(module)

    def code(self, module: ast.Module) -> ModuleCode:
        """The compiled pass of one of the program's modules."""
        return self._codes[id(module)]

    def _compile_module(self, module: ast.Module) -> ModuleCode:
        given: list[str] = []
        for param in module.params:
            given.extend(name for name in param.variables if name not in given)
        order = module.order or _DEFAULT_ORDER[module.kind]
        clause = self._compile_rules(module, module.rules, tuple(given), order)
        return ModuleCode(module, clause, tuple(given))

    def _compile_rules(self, module: ast.Module, rules: Sequence[ast.Rule],
                       given: tuple[str, ...], order: str) -> Atom:
        """The pass applying ``rules`` (each given ``given``) in ``order``."""
        names = [self._compile_rule(module, rule, given, order) for rule in rules]
        stop = order in ("linear", "random", "adaptive")
        shuffled = order in ("random", "randomall")
        key = ("pass", stop, shuffled, tuple(names))
        name = _shared_clauses.get(key)
        if name is None:
            name = self._engine.unique_name("$ga_p")
            self._state.call("compile_pass", Atom(name), _TRUE if stop else _FALSE,
                             _TRUE if shuffled else _FALSE, [Atom(n) for n in names])
            _shared_clauses[key] = name
        return Atom(name)

    def _compile_rule(self, module: ast.Module, rule: ast.Rule, given: tuple[str, ...],
                      order: str) -> str:
        """The clause name of ``rule`` (compiled once per text and operators)."""
        condition = self._compile_condition(rule)
        if rule.kind == "listall":
            list_var = rule.list_var or ""
            names = tuple(name for name in given if name != list_var) + (list_var,)
            collected = [Atom(name) for name in listall_variables(rule, given)]
            kind: Term = Struct("listall", (collected, Atom(list_var)))
        else:
            names = tuple(name for name in given if name not in condition.names)
            names += condition.names
            kind = Atom(rule.kind)
        if rule.rules is not None:
            inner = self._compile_rules(module, rule.rules, names, order)
            body = f"rules({format_term(inner)}, [{', '.join(names)}])"
            recorded: frozenset[int] = frozenset()
        else:
            body = "actions([" + ", ".join(self._action_text(a, names)
                                           for a in rule.actions) + "])"
            recorded = frozenset(index for index, action in enumerate(rule.actions)
                                 if self._closed_by_precondition(action, names))
        info = register_rule(module, rule, names, recorded)
        key = ("rule", info.id, self._directives)
        name = _shared_clauses.get(key)
        if name is None:
            name = self._engine.unique_name("$ga_r")
            text = f"'$rule'([{', '.join(given)}], [{', '.join(names)}], {body})"
            cond = Struct("c", (Atom(condition.clause), [Atom(n) for n in condition.names]))
            try:
                self._state.call("compile_rule", self._state.belief_module, Atom(name),
                                 info.id, kind, cond, text)
            except KBError as err:
                raise KBError(f"{rule.pos}: {err}", rule.pos) from None
            _shared_clauses[key] = name
        return name

    def _compile_condition(self, rule: ast.Rule) -> CompiledCondition:
        """The rule's condition compiled in this agent (its own clause)."""
        try:
            return self._state.compile(rule.condition)
        except KBError as err:  # located once: at the literal when known, else the rule
            pos = err.pos or rule.pos
            raise KBError(f"{pos}: {err}", pos) from None

    def _action_text(self, action: ast.Action, bound: tuple[str, ...]) -> str:
        """An action as rules.pl performs it (see compile_rule/6)."""
        if isinstance(action, ast.SendAction):
            return (f"send({'true' if action.once else 'false'}, {MOODS[action.mood]}, "
                    f"({action.receiver.text}\n), ({action.content.text}\n))")
        if action.builtin:
            if action.name == "exit-module":
                return "exit_module"
            if action.name in ast.GOAL7_ACTIONS:
                args = ", ".join(f"({arg.text}\n)" for arg in action.args)
                return f"goal7({action.name}, [{args}])"
            return f"{action.name}(({action.args[0].text}\n))"
        head = format_term(Atom(action.name))
        if action.args:
            head += "(" + ", ".join(f"({arg.text}\n)" for arg in action.args) + ")"
        key = (action.name, action.arity)
        if key in self._specs:
            recorded = self._closed_by_precondition(action, bound)
            return f"do({head}, {'true' if recorded else 'false'})"
        args = ", ".join(f"({arg.text}\n)" for arg in action.args)
        return f"module({self._modules[key]}, [{args}])"

    def _closed_by_precondition(self, action: ast.Action, bound: tuple[str, ...]) -> bool:
        """A user action with variables the rule does not bind: only its precondition can
        close it, so the journal keeps the form it was performed in."""
        return (isinstance(action, ast.ActionCall) and not action.builtin
                and (action.name, action.arity) in self._specs
                and any(name not in bound for arg in action.args for name in arg.variables))

    # ------------------------------------------------------------------ running

    def plan(self, modules: Sequence[tuple[ast.Module, Mapping[str, Term]]], *,
             environment: bool, listen: bool, count_last: bool = False
             ) -> Term | PlanPredicate:
        """What :meth:`run` runs: ``modules`` (each with the values of its module's
        parameters) in turn, for an agent with or without an environment and listeners
        (``count_last``: count the last module's actions). Defined as a predicate of the
        agent's once when no module has parameters (a cycle's modules are the same every
        cycle), so a run puts nothing into the call."""
        flags = (_TRUE if environment else _FALSE, _TRUE if listen else _FALSE,
                 _TRUE if count_last else _FALSE)
        codes = [(self._codes[id(module)], values) for module, values in modules]
        modules = self._state.modules
        if any(code.given for code, _ in codes):
            return Struct("r", (*modules, *flags, [
                Struct("p", (code.clause, [values.get(name) for name in code.given]))
                for code, values in codes]))
        key = (tuple(code.clause for code, _ in codes), flags)
        defined = self._plans.get(key)
        if defined is None:
            defined = self._plans[key] = self._state.define_plan(Struct("r", (
                *modules, *flags, [Struct("p", (clause, [])) for clause in key[0]])))
        return defined

    def run(self, plan: Term | PlanPredicate, requests: Requests) -> RunOutcome:
        """Runs a plan (see :meth:`plan`) in one Prolog call, answering the interpreter's
        requests with ``requests``."""
        answerer = self._answerer
        if answerer is None or answerer.requests is not requests:
            answerer = self._answerer = Answerer(requests)
        answering.append(answerer)
        try:
            outcome, journal = self._state.run(plan)
        finally:
            answering.pop()
        return RunOutcome(outcome, self._engine, journal)
