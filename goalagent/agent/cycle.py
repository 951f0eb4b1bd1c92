"""The reasoning cycle: one agent, its mental state in SWI-Prolog, its modules and actions.

Each cycle: collect percepts and messages -> (init module, first cycle only) -> event
module -> main module (or the module in focus) -> blind commitment. The modules of a cycle
run in one call of the rule interpreter (see ``goalagent.agent.rules``); GOAL's semantics
are in docs/goal-language.md. Environments and other agents are reached through
``AgentIO`` and ``Postman``, so the agent knows nothing of EIS or scheduling.
"""

from __future__ import annotations

import dataclasses
import random
import sys
from collections.abc import Callable
from pathlib import Path
from typing import TextIO

from goalagent import ast
from goalagent.agent.actions import ActionFailed, AgentIO
from goalagent.agent.checks import update_formulas, validate_program
from goalagent.agent.errors import AgentError
from goalagent.agent.events import (
    Event,
    Listener,
    Tracer,
    goal_event,
    message_event,
    percepts_event,
    plain_variables,
    readable_text,
)
from goalagent.agent.messages import Postman
from goalagent.agent.modules import Focus, leave_focus
from goalagent.agent.problems import goal_text, warning_text
from goalagent.agent.reports import CycleReport, RunResult
from goalagent.agent.rules import RuleApplication
from goalagent.agent.timers import Timer, due_percepts
from goalagent.events import EventKind, ProblemKind
from goalagent.kb.engine import KBError, get_engine
from goalagent.kb.interpreter_requests import Problem
from goalagent.kb.limits import Limits
from goalagent.kb.mentalstate import MentalState
from goalagent.kb.terms import Struct, Term, format_term
from goalagent.parser import parse_agent, parse_agent_file

Bindings = dict[str, Term]


IDLE_WARNING_CYCLES = 100
"""An agent with goals left that has done nothing for this many cycles is warned about once."""


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
        idle_warning: int | None = IDLE_WARNING_CYCLES,
        limits: Limits | None = None,
    ) -> None:
        self.program = program
        self.name = name or program.name
        self.io = io
        self.postman = postman
        self._seed = seed
        self._random: random.Random | None = None  # made when first drawn from
        get_engine().seed_random(seed)  # Prolog's random/1, random_float, roulette choices
        self.output = output or sys.stdout
        self.listeners: list[Listener] = []
        if tracer is not None:
            self.listen(lambda event: tracer(event.agent, event.kind, event.text))
        self._warn = warn or (lambda message: print(message, file=sys.stderr))
        self.cycle = 0
        self.terminated = False
        self.total_actions = 0
        self.last_report: CycleReport | None = None
        self.report = CycleReport(0)  # the cycle in progress (the last one between cycles)
        self.focus: list[Focus] = []  # user modules the agent stays in, innermost last
        self.timers: dict[str, Timer] = {}  # GOAL 7's running timers, by name
        self.idle_warning = idle_warning
        self.idle_cycles = 0  # cycles in a row without action, new percept or message
        self._warned: dict[str, int] = {}  # each warning given: how often
        self.initialized_apart = False  # the init module ran on its own (initialize())
        validate_program(program)
        try:
            self.ms = MentalState(self.name, knowledge=program.knowledge, beliefs=program.beliefs,
                                  limits=limits)
            self.ms.declare_updates(update_formulas(program))
            if self.ms.limits.runs_code:  # (adopting asks whether a goal is believed: code)
                for goal in program.goals:
                    self.ms.adopt(goal)
                    for _, why in self.ms.take_unchecked():
                        self.warn(f"module {self._module_of(goal)}, goal at {goal.pos}: "
                                  f"checking whether {goal.text.strip()} is believed {why}; "
                                  "the goal is adopted")
            else:
                self.ms.declare_updates(program.goals)
            self._rules = RuleApplication(self)
            self._event = program.module("event")
            self._main = program.module("main")
        except KBError as err:
            pos = getattr(err, "pos", None)
            text = str(err)
            if pos is not None and not text.startswith(str(pos)):
                text = f"{pos}: {text}"
            text = plain_variables(text)  # Prolog's variable numbers mean nothing to users
            raise AgentError(text if pos else f"{program.file}: {text}") from None

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_file(cls, path: str | Path, **kwargs) -> Agent:
        """Load an agent from a `.goal` file (``GoalSyntaxError`` on a malformed one)."""
        return cls(parse_agent_file(path), **kwargs)

    @classmethod
    def from_string(cls, text: str, file: str = "<string>", **kwargs) -> Agent:
        """Load an agent from program text."""
        return cls(parse_agent(text, file), **kwargs)

    # ------------------------------------------------------------------ public API
    @property
    def random(self) -> random.Random:
        """The agent's own random numbers (random rule orders), seeded with its seed when
        first drawn from: a generator holds 2.5 KB, and most agents never draw."""
        if self._random is None:
            self._random = random.Random(self._seed)
        return self._random

    def step(self) -> CycleReport:
        """Run one reasoning cycle (the first one also runs the init module)."""
        if self.terminated:
            raise AgentError(f"agent {self.name} has terminated")
        self.cycle += 1
        self.report = CycleReport(self.cycle)
        if self.io is not None or self.postman is not None or self.timers:
            self._perceive()  # (without them, no percepts and no messages: nothing to do)
        if self.focus:
            focus = self.focus[-1]
            modules = [(self._event, {})] if self._event is not None else []
            modules.append((focus.module, focus.bindings))
            outcome = self._rules.run_modules(modules, count_last=True)
            exit_option = focus.module.exit or "always"
            if (outcome.exited or (exit_option == "nogoals" and not self.ms.goals())
                    or (exit_option == "noaction" and outcome.last_actions == 0)):
                leave_focus(self)
        else:
            rules = self._rules
            first = self.cycle == 1 and not self.initialized_apart  # init runs first
            plan = rules.cycle_plans[first, bool(self.listeners)]
            if plan is not None:
                rules.run_plan(plan)
            main = self._main
            if main is not None:
                if main.exit is not None:  # (default: never)
                    self._check_main_exit(main.exit)
            elif not first or not self.program.module("init"):
                self.terminated = True  # nothing left to do without a main module
        if self.ms.goals_unchecked:
            self._blind_commitment()
        self._note_idleness()
        self.last_report = self.report
        return self.report

    def initialize(self) -> CycleReport:
        """Run the init module on its own, before the first cycle (GOAL 5's tests say
        ``do init.``): the first cycle then runs only the event and main modules."""
        if self.cycle > 0 or self.initialized_apart:
            raise AgentError(f"agent {self.name} has already started")
        self.initialized_apart = True
        self.report = CycleReport(0)
        if self.io is not None or self.postman is not None:
            self._perceive()
        init = self.program.module("init")
        if init is not None:
            self._rules.run_modules([(init, {})])
        self._blind_commitment()
        self.last_report = self.report
        return self.report

    def perform(self, actions: tuple[ast.Action, ...], pos: ast.Pos) -> CycleReport:
        """A test's ``do a + b`` of actions or modules other than main: percepts and messages
        are read, the actions done once (as the rule ``if true then a + b``), the goals
        achieved dropped; it counts as a cycle."""
        if self.terminated:
            raise AgentError(f"agent {self.name} has terminated")
        self.cycle += 1
        self.report = CycleReport(self.cycle)
        if self.io is not None or self.postman is not None or self.timers:
            self._perceive()
        rule = ast.Rule("if", (ast.MentalLiteral("true", None, pos),), pos, actions=actions)
        self._rules.run_once(ast.Module("do", "user", pos, rules=(rule,), order="linear"))
        self._blind_commitment()
        self.last_report = self.report
        return self.report

    def run(self, max_cycles: int | None = None) -> RunResult:
        """Cycle until the agent terminates or ``max_cycles`` cycles have run."""
        while not self.terminated and (max_cycles is None or self.cycle < max_cycles):
            self.step()
        return RunResult(self.cycle, self.terminated, self.total_actions, self.goals())

    def query(self, op: str, text: str, *, confined: bool = False,
              limit: int | None = None) -> list[Bindings]:
        """Answers of ``op(text)`` (bel, goal, a-goal, goal-a, percept) as Python values (the
        first ``limit``); ``confined``: checked as the agent's own code is, in its sandbox if
        it has one (a query a user types in the debugger or the inspector)."""
        return self.ms.query(op, text, trusted=not confined, limit=limit)

    def beliefs(self) -> list[Term]:
        return self.ms.beliefs()

    def goals(self) -> list[list[Term]]:
        return self.ms.goals()

    def close(self) -> None:
        """Free the agent's Prolog module."""
        self.ms.close()

    def listen(self, listener: Listener) -> None:
        """Tell ``listener`` every event from now on (the trace, an inspector)."""
        self.listeners.append(listener)

    def tell(self, event: Event) -> None:
        """Tell the listeners an event (stamped with the current cycle; fresh variables in its
        text shown as ``_``)."""
        event = dataclasses.replace(event, cycle=self.cycle, text=readable_text(event))
        for listener in self.listeners:
            listener(event)

    def warn(self, message: str) -> None:
        """A warning: kept in the cycle report, shown (``warning: agent NAME: ...``) and
        told to the listeners. A warning given before is shown again once, saying so, and
        then no more (a rule failing every cycle would otherwise fill the screen). Prolog's
        variable numbers are left out of it (``f(_)``), so a repeat reads the same."""
        message = plain_variables(message)
        self.report.warnings.append(message)
        seen = self._warned.get(message, 0)
        self._warned[message] = seen + 1
        if seen == 0:
            self._warn(f"warning: agent {self.name}: {message}")
        elif seen == 1:
            self._warn(f"warning: agent {self.name}: again in cycle {self.cycle} (not shown "
                       f"again): {message}")
        if self.listeners:
            self.tell(Event(EventKind.WARNING, self.name, message))

    def log(self, message: str) -> None:
        """A line where warnings go (``log/1``), not a warning."""
        self._warn(message)

    # ------------------------------------------------------------------ cycle parts
    def _perceive(self) -> None:
        percepts: list[Term] = []
        if self.io is not None:
            try:
                percepts = self.io.percepts()
            except ActionFailed as err:
                self.warn(warning_text(Problem(ProblemKind.PERCEPTS_UNAVAILABLE, str(err)),
                                       self.program))
        if self.timers:
            percepts = percepts + due_percepts(self)
        self.ms.set_percepts(percepts)
        self.report.percepts = percepts
        if percepts and self.listeners:
            self.tell(percepts_event(self.name, percepts))
        if self.postman is not None:
            messages = self.postman.collect(self.name)
            self.ms.receive(messages, replace=self.program.messages_for_one_cycle)
            if self.listeners:
                for sender, mood, content in messages:
                    self.tell(message_event(self.name, sender, mood, content))
            self.report.messages = messages

    def _check_main_exit(self, exit_option: str) -> None:
        """The main module's exit option (nogoals, noaction, always) after its pass."""
        if exit_option == "nogoals" and not self.ms.goals():
            self.terminated = True
        elif exit_option == "noaction" and not self.report.acted:
            self.terminated = True
        elif exit_option == "always":
            self.terminated = True

    def _note_idleness(self) -> None:
        """Count cycles in which nothing happened; say once when there have been
        ``idle_warning`` of them in a row while goals are left (an agent that would
        otherwise run on without a word)."""
        report, last = self.report, self.last_report
        if (report.acted or report.messages or self.terminated or last is None
                or report.percepts != last.percepts):
            self.idle_cycles = 0
            return
        self.idle_cycles += 1
        if self.idle_cycles == self.idle_warning:
            goals = self.goals()
            if goals:
                first = ", ".join(format_term(fact) for fact in goals[0])
                self.warn(f"has done nothing for {self.idle_cycles} cycles (no action, no new "
                          f"percept or message) and has {len(goals)} goal(s) left, e.g. "
                          f"{first}: no rule applies to them; it runs on until --max-cycles "
                          "or Ctrl-C")

    def _blind_commitment(self) -> None:
        for goal in self.ms.blind_commitment():
            if self.listeners:
                self.tell(goal_event(self.name, EventKind.GOAL_ACHIEVED, goal))
        for facts, why in self.ms.take_unchecked():
            self.warn(f"{self._goal_origin(facts)}: checking whether goal {goal_text(facts)} "
                      f"is achieved {why}; the goal is kept")

    def _module_of(self, goal: ast.PrologText) -> str:
        """The module whose goals section holds ``goal``."""
        return next((module.name for module in self.program.modules
                     if any(written is goal for written in module.goals)), "init")

    def _goal_origin(self, facts: list[Term]) -> str:
        """Where a goal was written, if it is one of the program's goals sections' (else
        the program's file and the module running)."""
        written = facts[0] if len(facts) == 1 else _conjunction(facts)
        for goal in self.program.goals:
            if self.ms.unify(goal, written) is not None:
                return f"module {self._module_of(goal)}, goal at {goal.pos}"
        module = self.focus[-1].module.name if self.focus else "main"
        return f"module {module}, {self.program.file}"


def _conjunction(facts: list[Term]) -> Term:
    """``(f1, f2, ...)`` of a goal's facts."""
    term = facts[-1]
    for fact in reversed(facts[:-1]):
        term = Struct(",", (fact, term))
    return term
