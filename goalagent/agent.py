"""The reasoning cycle: one agent, its mental state in SWI-Prolog, its modules and actions.

Each cycle: collect percepts and messages -> event module -> main module (or the module in
focus) -> blind commitment. Rules are tried in the module's order; a rule fires with the first
instantiation of its condition for which its action is enabled (GOAL's semantics; see
docs in ../shared/docs/goal-language.md). Environments and other agents are reached through
``AgentIO`` and ``Postman`` so that this file knows nothing of EIS or scheduling.

Without a tracer, rules run compiled: each rule's condition and the leading actions Prolog
can do are one Prolog clause, runs of such rules one call per module pass (see
``MentalState.compile_rule``/``compile_pass``); Python does the actions that need it (the
environment, print/log, messages, module calls) and builds the cycle report's entries only
when read. With a tracer every rule and action is done step by step here, so that the trace
shows each one; both paths give the same results.
"""

from __future__ import annotations

import random
import sys
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Protocol, TextIO

from goalagent import ast
from goalagent.kb.engine import KBError, PrologRuntimeError, get_engine
from goalagent.kb.mentalstate import (
    CompiledCondition,
    CompiledPass,
    CompiledRule,
    Firings,
    LazyBindings,
    MentalState,
    Problem,
    instantiate,
)
from goalagent.kb.terms import Atom, Struct, Term, Var, format_term
from goalagent.parser import (
    GoalSyntaxError,
    iter_rules,
    parse_agent,
    parse_agent_file,
    rename_variables,
)

Bindings = dict[str, Term]

_DEFAULT_ORDER = {"init": "linearall", "event": "linearall", "main": "linear", "user": "linear"}
_UPDATES = frozenset({"insert", "delete", "adopt", "drop"})  # built-ins a rule clause does
_BUILTIN_ARITY = {"insert": None, "delete": None, "adopt": None, "drop": None, "print": 1,
                  "log": 1, "exit-module": 0}


class AgentError(Exception):
    """A user error found when loading an agent (unknown action, bad clause, ...)."""


class ActionFailed(Exception):
    """Raised by an ``AgentIO`` when the environment could not perform an action."""


class AgentIO(Protocol):
    """What an agent needs from its environment (an EIS entity, or nothing)."""

    def percepts(self) -> list[Term]: ...

    def act(self, action: Struct | Atom) -> None: ...


class Postman(Protocol):
    """Message delivery between the agents of one system."""

    def agents(self) -> list[str]: ...

    def deliver(self, sender: str, receivers: list[str], mood: str, content: Term) -> None: ...

    def collect(self, receiver: str) -> list[tuple[str, str, Term]]: ...


class LocalPostman:
    """A postman for one or more agents in this process: messages wait until collected."""

    def __init__(self) -> None:
        self._boxes: dict[str, list[tuple[str, str, Term]]] = {}

    def register(self, name: str) -> None:
        self._boxes.setdefault(name, [])

    def agents(self) -> list[str]:
        return list(self._boxes)

    def deliver(self, sender: str, receivers: list[str], mood: str, content: Term) -> None:
        for receiver in receivers:
            if receiver not in self._boxes:
                raise ActionFailed(f"no agent called {receiver!r} to send to")
            self._boxes[receiver].append((sender, mood, content))

    def collect(self, receiver: str) -> list[tuple[str, str, Term]]:
        messages, self._boxes[receiver] = self._boxes.get(receiver, []), []
        return messages


# ----------------------------------------------------------------------------- reports


# An action performed: its description, or the action and its bindings to describe it when
# asked (formatting every action of every cycle costs more than most cycles' reasoning).
Performed = str | tuple[ast.ActionCall, Bindings | LazyBindings]


def _resolve(bindings: Bindings | LazyBindings) -> Bindings:
    """Bindings as Python values (a compiled rule's are read from Prolog on first use)."""
    return bindings.resolve() if isinstance(bindings, LazyBindings) else bindings


def _describe(item: Performed) -> str:
    """The description of a performed action (``insert(cycle(2))``)."""
    if isinstance(item, str):
        return item
    action, bindings = item
    if not action.args:
        return action.name
    if not action.builtin:  # a user action done by a rule clause
        values = _resolve(bindings)
        args = tuple(instantiate(arg, values) for arg in action.args)
        return format_term(Struct(action.name, args))
    values = {name: format_term(value) for name, value in _resolve(bindings).items()}
    args = ", ".join(rename_variables(arg.text, values) for arg in action.args)
    return f"{action.name}({args})"


class FiredRule:
    """A rule that fired: where it is, with which bindings, and the actions it performed."""

    __slots__ = ("module", "pos", "_bindings", "performed")

    def __init__(self, module: str, pos: ast.Pos, bindings: Bindings | LazyBindings,
                 performed: tuple[Performed, ...]) -> None:
        self.module = module
        self.pos = pos
        self._bindings = bindings
        self.performed = performed

    def __repr__(self) -> str:
        return (f"FiredRule(module={self.module!r}, pos={self.pos!r}, "
                f"bindings={self.bindings!r}, actions={self.actions!r})")

    @property
    def bindings(self) -> Bindings:
        """The rule's variables (and those it was given) with their values."""
        return _resolve(self._bindings)

    @property
    def line(self) -> int:
        return self.pos.line

    @property
    def actions(self) -> tuple[str, ...]:
        """The descriptions of the actions the rule performed, in order."""
        return tuple(_describe(item) for item in self.performed)


class _Batch:
    """The rules one Prolog call applied (a compiled rule or pass): their FiredRule entries
    are made when someone reads the report."""

    __slots__ = ("module", "rules", "firings", "_fired")

    def __init__(self, module: str, rules: Sequence[ast.Rule], firings: Firings) -> None:
        self.module = module
        self.rules = rules  # in the order tried
        self.firings = firings
        self._fired: list[FiredRule] | None = None

    def fired(self) -> list[FiredRule]:
        """The rules that fired, one entry per firing, in order."""
        if self._fired is None:
            self._fired = []
            for place, bindings, done in self.firings.items():
                rule = self.rules[place]
                performed = tuple((action, bindings) for action in rule.actions[:done])
                self._fired.append(FiredRule(self.module, rule.pos, bindings, performed))
        return self._fired


@dataclass
class CycleReport:
    """What happened in one cycle (for tests, traces and the CLI)."""

    cycle: int
    percepts: list[Term] = field(default_factory=list)
    messages: list[tuple[str, str, Term]] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    # In the order they happened: rules that fired, actions performed; a _Batch stands for
    # what one Prolog call did (expanded when read, so a report nobody reads costs little).
    entries: list[FiredRule | _Batch] = field(default_factory=list, repr=False)
    performed: list[Performed | _Batch] = field(default_factory=list, repr=False)

    @property
    def fired(self) -> list[FiredRule]:
        """The rules that fired in the cycle, in order."""
        result: list[FiredRule] = []
        for entry in self.entries:
            if isinstance(entry, _Batch):
                result.extend(entry.fired())
            else:
                result.append(entry)
        return result

    @property
    def actions(self) -> list[str]:
        """The descriptions of the actions performed in the cycle, in order."""
        result: list[str] = []
        for item in self.performed:
            if isinstance(item, _Batch):
                result.extend(_describe(done) for fired in item.fired() for done in fired.performed)
            else:
                result.append(_describe(item))
        return result

    @property
    def acted(self) -> bool:
        return bool(self.performed)


@dataclass(frozen=True)
class RunResult:
    """The outcome of ``Agent.run``."""

    cycles: int
    terminated: bool
    actions: int
    goals_left: list[list[Term]]


class Tracer(Protocol):
    """Receives trace events (``--trace``); ``kind`` names the event, ``text`` describes it."""

    def __call__(self, agent: str, kind: str, text: str) -> None: ...


# ----------------------------------------------------------------------------- agent


class _ExitModule(Exception):
    """``exit-module`` was performed: leave the current module."""


@dataclass
class _Focus:
    """A user module the agent stays in across cycles (exit other than always)."""

    module: ast.Module
    bindings: Bindings
    own_goal_base: bool


class Agent:
    """A GOAL agent: program + mental state + reasoning cycle."""

    def __init__(
        self,
        program: ast.AgentProgram,
        *,
        name: str | None = None,
        io: AgentIO | None = None,
        postman: Postman | None = None,
        seed: int = 0,
        output: TextIO | None = None,
        tracer: Tracer | None = None,
        warn: Callable[[str], None] | None = None,
    ) -> None:
        self.program = program
        self.name = name or program.name
        self.io = io
        self.postman = postman
        self.random = random.Random(seed)
        get_engine().seed_random(seed)  # Prolog's random/1, random_float, roulette choices
        self.output = output or sys.stdout
        self.tracer = tracer
        self._warn = warn or (lambda message: print(message, file=sys.stderr))
        self.cycle = 0
        self.terminated = False
        self.total_actions = 0
        self.last_report: CycleReport | None = None
        self._report = CycleReport(0)
        self._focus: list[_Focus] = []
        self._specs = _index_actionspecs(program.actionspecs)
        self._modules = _callable_modules(program)
        validate_program(program)
        try:
            self.ms = MentalState(self.name, knowledge=program.knowledge, beliefs=program.beliefs)
            self.ms.declare_updates(_update_formulas(program))
            for goal in program.goals:
                self.ms.adopt(goal)
        except KBError as err:
            pos = getattr(err, "pos", None)
            raise AgentError(f"{pos or program.file}: {err}") from None
        self._compiled: dict[int, object] = {}
        self._rule_clauses: dict[int, CompiledRule | None] = {}
        self._actions_declared = False  # actionspecs known to rule clauses
        self._pass_plans: dict[tuple[int, str, bool], list[ast.Rule | CompiledPass]] = {}
        self._pass_members: dict[int, tuple[ast.Rule, ...]] = {}
        self._compile_all()

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_file(cls, path: str | Path, **kwargs) -> Agent:
        """Load an agent from a `.goal` file (``GoalSyntaxError`` on a malformed one)."""
        return cls(parse_agent_file(path), **kwargs)

    @classmethod
    def from_string(cls, text: str, file: str = "<string>", **kwargs) -> Agent:
        """Load an agent from program text."""
        return cls(parse_agent(text, file), **kwargs)

    def _compile_all(self) -> None:
        for module in self.program.modules:
            for rule in iter_rules(module.rules):
                self._compiled[id(rule.condition)] = self.ms.compile(rule.condition)
        for specs in self._specs.values():
            for spec in specs:
                condition = (ast.MentalLiteral("bel", spec.pre, spec.pos),)
                self._compiled[id(spec)] = self.ms.compile(condition)

    # ------------------------------------------------------------------ public API
    def step(self) -> CycleReport:
        """Run one reasoning cycle (the first one also runs the init module)."""
        if self.terminated:
            raise AgentError(f"agent {self.name} has terminated")
        self.cycle += 1
        self._report = CycleReport(self.cycle)
        self._perceive()
        if self.cycle == 1:
            self._run_named("init")
        self._run_named("event")
        if self._focus:
            self._run_focus()
        else:
            main = self.program.module("main")
            if main is not None:
                self._run_module(main, {})
                self._check_main_exit(main)
            elif self.cycle > 1 or not self.program.module("init"):
                self.terminated = True  # nothing left to do without a main module
        self._blind_commitment()
        self.last_report = self._report
        return self._report

    def run(self, max_cycles: int | None = None) -> RunResult:
        """Cycle until the agent terminates or ``max_cycles`` cycles have run."""
        while not self.terminated and (max_cycles is None or self.cycle < max_cycles):
            self.step()
        return RunResult(self.cycle, self.terminated, self.total_actions, self.goals())

    def query(self, op: str, text: str) -> list[Bindings]:
        """Answers of ``op(text)`` (bel, goal, a-goal, goal-a, percept) as Python values."""
        return self.ms.query(op, text)

    def beliefs(self) -> list[Term]:
        return self.ms.beliefs()

    def goals(self) -> list[list[Term]]:
        return self.ms.goals()

    def close(self) -> None:
        """Free the agent's Prolog module."""
        self.ms.close()

    # ------------------------------------------------------------------ cycle parts
    def _trace(self, kind: str, text: str) -> None:
        if self.tracer is not None:
            self.tracer(self.name, kind, text)

    def warn(self, message: str) -> None:
        self._report.warnings.append(message)
        self._warn(f"warning: agent {self.name}: {message}")

    def _perceive(self) -> None:
        percepts: list[Term] = []
        if self.io is not None:
            try:
                percepts = self.io.percepts()
            except ActionFailed as err:
                self.warn(f"could not get percepts: {err}")
        self.ms.set_percepts(percepts)
        self._report.percepts = percepts
        if percepts and self.tracer is not None:  # formatting them costs: only for a tracer
            self._trace("percepts", ", ".join(format_term(p) for p in percepts))
        if self.postman is not None:
            messages = self.postman.collect(self.name)
            for sender, mood, content in messages:
                self.ms.add_received(sender, mood, content)
                if self.tracer is not None:
                    self._trace("received", f"{sender}: {mood}{format_term(content)}")
            self._report.messages = messages

    def _run_named(self, name: str) -> None:
        module = self.program.module(name)
        if module is not None:
            self._run_module(module, {})

    def _check_main_exit(self, main: ast.Module) -> None:
        exit_option = main.exit or "never"
        if exit_option == "nogoals" and not self.ms.goals():
            self.terminated = True
        elif exit_option == "noaction" and not self._report.acted:
            self.terminated = True
        elif exit_option == "always":
            self.terminated = True

    def _run_focus(self) -> None:
        focus = self._focus[-1]
        acted_before = len(self._report.performed)
        exited = self._run_module(focus.module, focus.bindings)
        exit_option = focus.module.exit or "always"
        if (
            exited
            or (exit_option == "nogoals" and not self.ms.goals())
            or (exit_option == "noaction" and len(self._report.performed) == acted_before)
        ):
            self._leave_focus()

    def _leave_focus(self) -> None:
        focus = self._focus.pop()
        if focus.own_goal_base:
            self.ms.pop_goal_base()
        self._trace("module", f"leaving module {focus.module.name}")

    def _blind_commitment(self) -> None:
        for goal in self.ms.blind_commitment():
            if self.tracer is not None:
                self._trace("goal", f"achieved and dropped: {_format_goal(goal)}")

    # ------------------------------------------------------------------ modules and rules
    def _run_module(self, module: ast.Module, bindings: Bindings) -> bool:
        """One pass over the module's rules; True when ``exit-module`` was performed."""
        order = module.order or _DEFAULT_ORDER[module.kind]
        try:
            self._run_rules(module, module.rules, bindings, order)
        except _ExitModule:
            return True
        return False

    def _run_rules(
        self, module: ast.Module, rules: tuple[ast.Rule, ...], bindings: Bindings, order: str
    ) -> bool:
        """Evaluate rules in ``order``; True when at least one fired."""
        sequence: list[ast.Rule | CompiledPass]
        shuffled: list[int] = []
        if bindings:
            sequence = list(rules)
        else:
            sequence = self._passes(rules, order)
        if order in ("random", "randomall"):
            if len(sequence) == 1 and isinstance(sequence[0], CompiledPass):
                shuffled = list(range(len(rules)))  # the pass tries the rules in this order
                self.random.shuffle(shuffled)
            else:
                sequence = list(rules)
                self.random.shuffle(sequence)
        fired_any = False
        for item in sequence:
            if isinstance(item, CompiledPass):
                fired = self._apply_pass(module, item, shuffled)
            else:
                fired = self._apply_rule(module, item, bindings, order)
            if fired:
                fired_any = True
                if order in ("linear", "random", "adaptive"):
                    break
        return fired_any

    def _passes(self, rules: tuple[ast.Rule, ...], order: str) -> list[ast.Rule | CompiledPass]:
        """``rules`` with every run of two or more consecutive rules that compile whole (all
        actions built in) grouped into one compiled pass: one Prolog call applies the run."""
        key = (id(rules), order, self.tracer is None)
        cached = self._pass_plans.get(key)
        if cached is not None:
            return cached
        plan: list[ast.Rule | CompiledPass] = []
        run: list[ast.Rule] = []
        for rule in (*rules, None):
            clause = self._rule_clause(rule) if rule is not None else None
            if (clause is not None and not clause.pending
                    and clause.actions == len(rule.actions)):  # type: ignore[union-attr]
                run.append(rule)  # type: ignore[arg-type]
                continue
            if len(run) >= 2:
                clauses = [self._rule_clauses[id(member)] for member in run]
                stop = order in ("linear", "random", "adaptive")
                compiled = self.ms.compile_pass(clauses, stop=stop)  # type: ignore[arg-type]
                self._pass_members[id(compiled)] = tuple(run)
                plan.append(compiled)
            else:
                plan.extend(run)
            run = []
            if rule is not None:
                plan.append(rule)
        self._pass_plans[key] = plan
        return plan

    def _apply_pass(self, module: ast.Module, compiled: CompiledPass,
                    order: list[int]) -> bool:
        """Applies a compiled pass, its rules in ``order`` (indices; empty: as written);
        True when one of its rules fired."""
        members = self._pass_members[id(compiled)]
        if order:
            members = tuple(members[index] for index in order)
        firings = self.ms.fire_pass(compiled, order)
        return self._note(module, members, firings)

    def _note(self, module: ast.Module, rules: Sequence[ast.Rule], firings: Firings) -> bool:
        """Reports what a compiled rule or pass did (``rules`` in the order tried); True
        when a rule fired."""
        for place, problem in firings.problems:
            self._problem(module, rules[place], problem)
        if not firings:
            return False
        batch = _Batch(module.name, rules, firings)
        self._report.entries.append(batch)
        self._report.performed.append(batch)
        self.total_actions += firings.actions
        return True

    def _solutions(self, module: ast.Module, rule: ast.Rule, bindings: Bindings,
                   limit: int | None = None) -> list[Bindings]:
        try:
            return self.ms.solutions(self._compiled[id(rule.condition)], bindings, limit=limit)
        except PrologRuntimeError as err:
            self.warn(f"module {module.name}, rule at {rule.pos}: Prolog error in the "
                      f"condition: {err.message}; the rule is not applicable")
            return []

    def _problem(self, module: ast.Module, rule: ast.Rule, problem: Problem) -> None:
        """Warns about a problem a compiled rule met, as the step-by-step path words it."""
        kind, index, detail = problem
        if kind == "condition":
            self.warn(f"module {module.name}, rule at {rule.pos}: Prolog error in the "
                      f"condition: {detail}; the rule is not applicable")
        elif kind == "pre":
            spec = self.program.actionspecs[index]  # type: ignore[index]
            self.warn(f"precondition of {spec.name} at {spec.pos}: Prolog error: "
                      f"{detail}; the action is not enabled")
        elif kind == "open":
            pos = rule.actions[index].pos  # type: ignore[index]
            self.warn(f"{pos}: action {format_term(detail)} is not closed after its "
                      "precondition; not performed")
        else:
            action = rule.actions[index]  # type: ignore[index]
            self.warn(f"{action.pos}: {action.name} failed: {detail}")

    def _in_prolog(self, action: ast.Action,
                   condition: CompiledCondition) -> tuple[str, str] | None:
        """How a rule clause performs ``action`` itself (see ``RULE_ACTIONS`` in
        goalagent.kb.mentalstate): "env" for an action that may go to the environment (the
        clause checks its precondition, Python does the rest). None when Python must do it
        all: messages, print/log, module calls, exit-module, and user actions with a
        variable the condition does not bind (their precondition's bindings do not flow
        into the rest of the rule)."""
        if not isinstance(action, ast.ActionCall):
            return None
        if action.builtin and action.name in _UPDATES:
            return (action.name, action.args[0].text)
        specs = self._specs.get((action.name, action.arity))
        if not specs:
            return None
        kind = "do" if self.io is None or all(spec.internal for spec in specs) else "env"
        bound = set(condition.names)
        if any(name not in bound for arg in action.args for name in arg.variables):
            return None
        if not self._actions_declared:
            self.ms.declare_actions(self.program.actionspecs)
            self._actions_declared = True
        text = format_term(Atom(action.name))
        if action.args:
            text += "(" + ", ".join(arg.text for arg in action.args) + ")"
        return (kind, text)

    def _rule_clause(self, rule: ast.Rule) -> CompiledRule | None:
        """The rule compiled with its leading actions that Prolog can do (see
        :meth:`_in_prolog`) into one Prolog clause (compiled on first use), or None when
        Python must do everything: a tracer is set (it sees each step), the rule is nested
        or listall, its first action needs Python, or it is a forall whose actions do not
        all run in Prolog (every instantiation must finish its combo before the next one
        starts). An action for the environment ends the clause's actions."""
        if self.tracer is not None:
            return None
        key = id(rule)
        if key in self._rule_clauses:
            return self._rule_clauses[key]
        condition = self._compiled[id(rule.condition)]
        assert isinstance(condition, CompiledCondition)
        leading = []
        for action in rule.actions:
            done_here = self._in_prolog(action, condition)
            if done_here is None:
                break
            leading.append(done_here)
            if done_here[0] == "env":
                break
        whole = len(leading) == len(rule.actions) and all(kind != "env" for kind, _ in leading)
        clause = None
        if rule.rules is None and leading and (
            rule.kind == "if" or (rule.kind == "forall" and whole)
        ):
            try:
                clause = self.ms.compile_rule(rule.kind, condition, leading)
            except KBError as err:
                raise AgentError(f"{rule.pos}: {err}") from None
        self._rule_clauses[key] = clause
        return clause

    def _apply_rule(self, module: ast.Module, rule: ast.Rule, bindings: Bindings,
                    order: str) -> bool:
        clause = self._rule_clause(rule)
        if clause is not None:
            return self._apply_clause(module, rule, clause, bindings, order)
        solutions = self._solutions(module, rule, bindings)
        self._trace("rule", f"{module.name} {rule.pos}: {len(solutions)} instantiation(s)")
        if rule.kind == "listall":
            values = [solution.get(_listall_var(rule)) for solution in solutions]
            bound = {**bindings, rule.list_var: values}
            return self._fire(module, rule, bound, order)
        fired = False
        for solution in solutions:
            if self._fire(module, rule, solution, order):
                fired = True
                if rule.kind == "if":
                    break
        return fired

    def _apply_clause(self, module: ast.Module, rule: ast.Rule, clause: CompiledRule,
                      bindings: Bindings, order: str) -> bool:
        """Applies a rule through its one-clause form; actions after the clause's leading
        ones are done here, as :meth:`_fire` does them."""
        try:
            firings = self.ms.fire(clause, bindings)
        except PrologRuntimeError as err:
            self.warn(f"module {module.name}, rule at {rule.pos}: Prolog error in the "
                      f"condition: {err.message}; the rule is not applicable")
            return False
        if clause.actions == len(rule.actions) and not clause.pending:
            return self._note(module, (rule,), firings)
        for _, problem in firings.problems:
            self._problem(module, rule, problem)
        if not firings:
            return False
        report = self._report
        fired = False
        for _, solution, done in firings.items():
            go_on = done == clause.actions  # the rest of the combo is Python's
            pending = clause.pending and go_on  # the last action was left to Python
            in_prolog = done - 1 if pending else done
            performed: list[Performed] = [(action, solution)
                                          for action in rule.actions[:in_prolog]]
            report.performed.extend(performed)
            self.total_actions += in_prolog
            if pending:  # an environment action, enabled and closed: Python performs it
                left = firings.pending()
                assert left is not None
                term, post, spec = left
                action = rule.actions[in_prolog]
                assert isinstance(action, ast.ActionCall)
                description = self._act_on(action, self.program.actionspecs[spec], term,
                                           lambda post=post: self.ms.insert_term(post))
                if description is None:
                    go_on = False  # an internal action whose postcondition failed
                else:
                    performed.append(description)
            if go_on:
                fired = self._fire(module, rule, solution.resolve(), order, start=done,
                                   performed=performed) or fired
            elif performed:
                report.entries.append(FiredRule(module.name, rule.pos, solution,
                                                tuple(performed)))
                fired = True
        return fired

    def _fire(self, module: ast.Module, rule: ast.Rule, bindings: Bindings, order: str,
              start: int = 0, performed: list[Performed] | None = None) -> bool:
        """Perform the rule's actions from ``start`` (or its nested rules) with ``bindings``,
        after the ``performed`` ones; True if it fired."""
        if rule.rules is not None:
            fired = self._run_rules(module, rule.rules, bindings, order)
            if fired:
                self._record(module, rule, bindings, ())
            return fired
        performed = performed or []
        try:
            for index in range(start, len(rule.actions)):
                action = rule.actions[index]
                description = self._perform(module, action, bindings, rule.condition)
                if description is None:
                    if index == 0:
                        return False  # not enabled: try the next instantiation or rule
                    break  # a combo stops at the first action that is not enabled
                performed.append(description)
        finally:
            if performed:
                self._record(module, rule, bindings, tuple(performed))
        return True

    def _record(self, module: ast.Module, rule: ast.Rule, bindings: Bindings,
                performed: tuple[Performed, ...]) -> None:
        self._report.entries.append(FiredRule(module.name, rule.pos, dict(bindings), performed))
        if self.tracer is not None:
            shown = ", ".join(f"{k}={format_term(v)}" for k, v in bindings.items())
            described = " + ".join(map(_describe, performed))
            self._trace("fired", f"{module.name} {rule.pos} [{shown}] -> {described}")

    # ------------------------------------------------------------------ actions
    def _perform(self, module: ast.Module, action: ast.Action, bindings: Bindings,
                 condition: ast.Condition = ()) -> Performed | None:
        """Perform one action (of a rule whose condition is ``condition``); its description,
        or None when it is not enabled."""
        if isinstance(action, ast.SendAction):
            return self._send(action, bindings)
        name = action.name
        if action.builtin:
            return self._builtin(module, action, bindings)
        key = (name, action.arity)
        if key in self._specs:
            return self._user_action(action, bindings)
        target = self._modules[key]  # validated at load time
        return self._call_module(target, action, bindings, condition)

    def _builtin(self, module: ast.Module, action: ast.ActionCall,
                 bindings: Bindings) -> Performed | None:
        name = action.name
        if name == "exit-module":
            self._act_done("exit-module")
            raise _ExitModule
        formula = action.args[0]
        try:
            if name in ("print", "log"):
                term = self.ms.instantiate(formula, bindings)
                if name == "print":
                    print(_plain(term), file=self.output, flush=True)
                else:
                    self._warn(f"log: agent {self.name}: {_plain(term)}")
            elif name == "insert":
                self._changes(self.ms.insert(formula, bindings))
            elif name == "delete":
                self._changes(self.ms.delete(formula, bindings))
            elif name == "adopt":
                if not self.ms.adopt(formula, bindings):
                    self._trace("action", f"adopt refused: {formula.text} (believed or a goal)")
                    return None
                if self.tracer is not None:
                    adopted = self.ms.instantiate(formula, bindings)
                    self._trace("goal", f"adopted {format_term(adopted)}")
            elif name == "drop":
                for goal in self.ms.drop(formula, bindings):
                    if self.tracer is not None:
                        self._trace("goal", f"dropped {_format_goal(goal)}")
        except KBError as err:
            self.warn(f"{action.pos}: {name} failed: {err}")
            return None
        return self._act_done((action, bindings))

    def _changes(self, changes: Iterable[tuple[str, Term]]) -> None:
        """Traces belief changes (formatted only when a tracer is set)."""
        if self.tracer is not None:
            for sign, term in changes:
                self._trace("belief", f"{sign}{format_term(term)}")

    def _act_done(self, description: Performed) -> Performed:
        self._report.performed.append(description)
        self.total_actions += 1
        self._blind_commitment()
        return description

    def _user_action(self, action: ast.ActionCall, bindings: Bindings) -> Performed | None:
        call_args = [self.ms.instantiate(arg, bindings) for arg in action.args]
        for spec in self._specs[(action.name, action.arity)]:
            spec_bindings: Bindings | None = {}
            for param, value in zip(spec.params, call_args, strict=True):
                spec_bindings = self.ms.unify(param, value, spec_bindings)
                if spec_bindings is None:
                    break
            if spec_bindings is None:
                continue
            try:
                answers = self.ms.solutions(self._compiled[id(spec)], spec_bindings, limit=1)
            except PrologRuntimeError as err:
                self.warn(f"precondition of {spec.name} at {spec.pos}: Prolog error: "
                          f"{err.message}; the action is not enabled")
                continue
            if not answers:
                if self.tracer is not None:
                    self._trace("precondition", f"{_describe((action, bindings))}: pre "
                                f"{{{spec.pre.text}}} does not hold")
                continue
            enabled = answers[0]
            term = _action_term(spec, self.ms, enabled)
            if _has_variables(term):
                self.warn(f"{action.pos}: action {format_term(term)} is not closed after its "
                          "precondition; not performed")
                return None
            return self._act_on(action, spec, term,
                                lambda post=spec.post, at=enabled: self.ms.insert(post, at))
        return None

    def _act_on(self, action: ast.ActionCall, spec: ast.ActionSpec, term: Term,
                post: Callable[[], list[tuple[str, Term]]]) -> Performed | None:
        """Performs an enabled user action: sends ``term`` to the environment (unless the
        spec is internal or there is none), then applies the postcondition (``post``);
        its description. A postcondition that fails is a warning; the action then counts as
        not performed (None) unless the environment already performed it."""
        text = format_term(term)
        sent = not spec.internal and self.io is not None
        if sent:
            try:
                self.io.act(term)  # type: ignore[union-attr, arg-type]
            except ActionFailed as err:
                self.warn(f"{action.pos}: the environment could not perform {text}: {err}")
                return self._act_done(text)
        try:
            self._changes(post())
        except KBError as err:
            self.warn(f"{action.pos}: {action.name} failed: {err}")
            if not sent:
                return None
        return self._act_done(text)

    def _call_module(self, module: ast.Module, action: ast.ActionCall, bindings: Bindings,
                     condition: ast.Condition) -> Performed | None:
        module_bindings: Bindings | None = {}
        for param, arg in zip(module.params, action.args, strict=True):
            module_bindings = self.ms.unify(param, self.ms.instantiate(arg, bindings),
                                            module_bindings)
            if module_bindings is None:
                return None
        description = _describe((action, bindings))
        self._trace("module", f"entering module {description}")
        own_goal_base = self._enter_goal_focus(module, condition, bindings)
        exit_option = (module.exit or "always") if module.kind == "user" else "always"
        actions_before = len(self._report.performed)
        exited = self._run_module(module, module_bindings)
        if exit_option == "always" or exited:
            if own_goal_base:
                self.ms.pop_goal_base()
        else:
            self._focus.append(_Focus(module, module_bindings, own_goal_base))
        self._report.performed.insert(actions_before, description)
        return description

    def _enter_goal_focus(self, module: ast.Module, condition: ast.Condition,
                          bindings: Bindings) -> bool:
        """Give the module its own goal base as its ``focus`` option says: ``new`` an empty
        one; ``filter`` the goals the calling rule's condition names (its goal, a-goal and
        goal-a literals, instantiated); ``select`` the current goals that contain them."""
        focus = module.focus or "none"
        if focus == "none":
            return False
        named = [_conjuncts(self.ms.instantiate(literal.query, bindings))
                 for literal in condition
                 if isinstance(literal, ast.MentalLiteral) and literal.query is not None
                 and literal.op in ("goal", "a-goal", "goal-a")]
        if focus == "new":
            self.ms.push_goal_base([])
        elif focus == "filter":
            self.ms.push_goal_base(named)
        else:
            wanted = [fact for facts in named for fact in facts]
            self.ms.push_goal_base([goal for goal in self.ms.goals()
                                    if all(fact in goal for fact in wanted)][:1])
        return True

    def _send(self, action: ast.SendAction, bindings: Bindings) -> Performed | None:
        receiver = self.ms.instantiate(action.receiver, bindings)
        content = self.ms.instantiate(action.content, bindings)
        text = f"{format_term(receiver)}.{action.name}({action.mood}{format_term(content)})"
        if _has_variables(receiver):
            self.warn(f"{action.pos}: the receiver of {text} is not bound; not sent")
            return None
        everyone = self.postman.agents() if self.postman is not None else [self.name]
        if receiver == "allother":
            receivers = [a for a in everyone if a != self.name]
        elif receiver == "all":
            receivers = list(everyone)
        else:
            receivers = [str(receiver)]
        fresh = [r for r in receivers
                 if self.ms.add_sent(r, action.mood, content) or not action.once]
        if action.once and not fresh:
            return None
        if self.postman is not None and fresh:
            try:
                self.postman.deliver(self.name, fresh, action.mood, content)
            except ActionFailed as err:
                self.warn(f"{action.pos}: {err}")
                return None
        return self._act_done(text)


# ----------------------------------------------------------------------------- helpers


def _index_actionspecs(specs: Iterable[ast.ActionSpec]) -> dict[tuple[str, int], list]:
    index: dict[tuple[str, int], list[ast.ActionSpec]] = {}
    for spec in specs:
        index.setdefault((spec.name, spec.arity), []).append(spec)
    return index


def validate_program(program: ast.AgentProgram) -> None:
    """Every action in a rule must be built in, specified or a user module (with its arity);
    raises ``GoalSyntaxError`` at the first one that is not."""
    specs = _index_actionspecs(program.actionspecs)
    modules = _callable_modules(program)
    for module in program.modules:
        for rule in iter_rules(module.rules):
            for action in rule.actions:
                if isinstance(action, ast.SendAction):
                    continue
                key = (action.name, action.arity)
                if action.builtin:
                    expected = _BUILTIN_ARITY[action.name]
                    if (expected is None and action.arity == 0) or (
                        expected is not None and action.arity != expected
                    ):
                        raise GoalSyntaxError.at(
                            action.pos, f"{action.name} takes "
                            f"{'an argument' if expected is None else expected} argument(s), "
                            f"not {action.arity}")
                elif key not in specs and key not in modules:
                    known = sorted(f"{n}/{a}" for n, a in (*specs, *modules))
                    raise GoalSyntaxError.at(
                        action.pos,
                        f"unknown action {action.name}/{action.arity}: not built in, not in an "
                        f"actionspec and not a module (known: {', '.join(known) or 'none'})",
                    )


def _callable_modules(program: ast.AgentProgram) -> dict[tuple[str, int], ast.Module]:
    """Modules an action can call: user modules, and init/main/event by name (GOAL allows it)."""
    return {(m.name, m.arity): m for m in program.modules}


def _update_formulas(program: ast.AgentProgram) -> list[ast.PrologText]:
    """Every formula the agent may insert or delete (so its predicates are dynamic)."""
    formulas = list(program.goals) + [spec.post for spec in program.actionspecs]
    for module in program.modules:
        for rule in iter_rules(module.rules):
            for action in rule.actions:
                if isinstance(action, ast.ActionCall) and action.builtin and (
                    action.name in _UPDATES
                ):
                    formulas.extend(action.args)
    return formulas


def _listall_var(rule: ast.Rule) -> str:
    """The variable whose values ``listall L <- C`` collects: the first one of C."""
    for literal in rule.condition:
        if isinstance(literal, ast.MentalLiteral) and literal.query is not None:
            for name in literal.query.variables:
                if name != rule.list_var and not name.startswith("_"):
                    return name
    return ""


def _action_term(spec: ast.ActionSpec, ms: MentalState, bindings: Bindings) -> Struct | Atom:
    if not spec.params:
        return Atom(spec.name)
    return Struct(spec.name, tuple(ms.instantiate(p, bindings) for p in spec.params))


def _conjuncts(term: Term) -> list[Term]:
    """The facts of a conjunction ``(a, b, c)``."""
    if isinstance(term, Struct) and term.name == "," and term.arity == 2:
        return _conjuncts(term.args[0]) + _conjuncts(term.args[1])
    return [term]


def _has_variables(term: Term) -> bool:
    if isinstance(term, Var):
        return True
    if isinstance(term, Struct):
        return any(_has_variables(arg) for arg in term.args)
    if isinstance(term, list):
        return any(_has_variables(item) for item in term)
    return False


def _plain(term: Term) -> str:
    """``print/1`` output: atoms and strings as their text, other terms as SWI-Prolog's
    ``writeq`` writes them (operators included: ``a-1``, not ``-(a,1)``)."""
    if isinstance(term, str):
        return str(term)
    return get_engine().write(term, quoted=True)


def _format_goal(goal: list[Term]) -> str:
    return ", ".join(format_term(fact) for fact in goal)
