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
    readable,
)
from goalagent.agent.messages import Postman
from goalagent.agent.modules import Focus, leave_focus
from goalagent.agent.problems import (
    cause_traceback,
    goal_origin,
    goal_text,
    module_of,
    warning_text,
)
from goalagent.agent.reports import CycleReport, RunResult
from goalagent.agent.rules import RuleApplication
from goalagent.agent.timers import Timer, due_percepts
from goalagent.events import EventKind, ProblemKind
from goalagent.kb.engine import KBError, get_engine
from goalagent.kb.interpreter_requests import Problem
from goalagent.kb.limits import Limits
from goalagent.kb.mentalstate import MentalState
from goalagent.kb.terms import Term, format_term
from goalagent.parser import parse_agent, parse_agent_file

Bindings = dict[str, Term]


IDLE_WARNING_CYCLES = 100
"""An agent with goals left that has done nothing for this many cycles is warned about once."""


class Agent:
    """A GOAL agent: its program, its mental state in SWI-Prolog and its reasoning cycle.

    Made from a file or a text (:meth:`from_file`, :meth:`from_string`), it runs a cycle at
    a time (:meth:`step`) or to the end (:meth:`run`) and answers queries on its mental
    state (:meth:`query`). Alone it has no environment: its user actions only do what their
    postconditions say. To put one agent in an environment, make a system of it
    (``MultiAgentSystem.for_agent_text(text, environment="blocksworld")``) and step
    ``system.agents[0]``; or pass ``io``, any object with ``percepts()`` and ``act(action)``.

    Args:
        program: the parsed program (``goalagent.parser.parse_agent``).
        name: the agent's name (default: the program's).
        io: its environment connection (``AgentIO``); None: no percepts, user actions only
            change the mental state.
        postman: delivers its messages (``LocalPostman`` in a system); None: messages go
            nowhere.
        seed: seeds the choice among a rule's instantiations, ``random`` orders and
            Prolog's random numbers.
        output: where ``print/1`` writes (default: stdout).
        tracer: called with (agent, kind, text) for every event (as ``--trace`` prints).
        warn: called with each warning line (default: printed on stderr).
        idle_warning: cycles without any action, new percept or message after which an
            agent with goals left is warned about once (None: never).
        limits: inferences, seconds, beliefs and the sandbox (default: ``Limits()``).

    Raises:
        AgentError: the program cannot be loaded (a clause SWI-Prolog refuses, a goal that
            is not ground, ...), with its file, line and column.
    """

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
        self.random = random.Random(seed)
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
                        self.warn(f"module {module_of(program, goal)}, goal at {goal.pos}: "
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
    def from_file(
        cls,
        path: str | Path,
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
    ) -> Agent:
        """Load an agent from a ``.goal`` file.

        Args:
            path: the agent file.
            name: the agent's name (default: the program's).
            io: its environment connection (None: none).
            postman: delivers its messages (None: messages go nowhere).
            seed: seeds its choices among instantiations and Prolog's random numbers.
            output: where ``print/1`` writes (default: stdout).
            tracer: called with (agent, kind, text) for every event.
            warn: called with each warning line (default: printed on stderr).
            idle_warning: idle cycles before the one warning about them (None: never).
            limits: inferences, seconds, beliefs and the sandbox (default ``Limits()``).

        Returns:
            The agent, before its first cycle.

        Raises:
            GoalSyntaxError: the file is malformed (its message is ``file:line:col: ...``).
            AgentError: the program cannot be loaded.
        """
        return cls(parse_agent_file(path), name=name, io=io, postman=postman, seed=seed,
                   output=output, tracer=tracer, warn=warn, idle_warning=idle_warning,
                   limits=limits)

    @classmethod
    def from_string(
        cls,
        text: str,
        file: str = "<string>",
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
    ) -> Agent:
        """Load an agent from program text (the single-file ``.goal`` format).

        Args:
            text: the program.
            file: the name its errors and positions give (default ``<string>``).
            name: the agent's name (default: the program's).
            io: its environment connection (None: none).
            postman: delivers its messages (None: messages go nowhere).
            seed: seeds its choices among instantiations and Prolog's random numbers.
            output: where ``print/1`` writes (default: stdout).
            tracer: called with (agent, kind, text) for every event.
            warn: called with each warning line (default: printed on stderr).
            idle_warning: idle cycles before the one warning about them (None: never).
            limits: inferences, seconds, beliefs and the sandbox (default ``Limits()``).

        Returns:
            The agent, before its first cycle.

        Raises:
            GoalSyntaxError: the text is malformed.
            AgentError: the program cannot be loaded.
        """
        return cls(parse_agent(text, file), name=name, io=io, postman=postman, seed=seed,
                   output=output, tracer=tracer, warn=warn, idle_warning=idle_warning,
                   limits=limits)

    # ------------------------------------------------------------------ public API
    def step(self) -> CycleReport:
        """Run one reasoning cycle (the first one also runs the init module).

        Returns:
            What the cycle did: the rules that fired with their bindings, the actions,
            percepts, messages and warnings.

        Raises:
            AgentError: the agent has terminated.
        """
        if self.terminated:
            raise AgentError(f"agent {self.name} has terminated")
        self.cycle += 1
        self.report = CycleReport(self.cycle)
        if self.io is not None or self.postman is not None or self.timers:
            self._perceive()  # (without them, no percepts and no messages: nothing to do)
        if self.focus:
            focus = self.focus[-1]
            modules: list[tuple[ast.Module, Bindings]] = (
                [(self._event, {})] if self._event is not None else [])
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
        """Cycle until the agent terminates or has run ``max_cycles`` cycles in all.

        Args:
            max_cycles: the most cycles (counted from its first); None: no bound.

        Returns:
            The cycles run, whether it terminated, its actions and the goals left.
        """
        while not self.terminated and (max_cycles is None or self.cycle < max_cycles):
            self.step()
        return RunResult(self.cycle, self.terminated, self.total_actions, self.goals())

    def query(self, op: str, text: str, *, confined: bool = False, sandboxed: bool = False,
              limit: int | None = None) -> list[Bindings]:
        """The answers of a mental-state query, as Python values.

        Args:
            op: ``bel``, ``goal``, ``a-goal``, ``goal-a`` or ``percept``.
            text: the query in Prolog (``count(X)``, ``on(X, Y), X \\= a``).
            confined: check it as the agent's own code is, in its sandbox if it has one (a
                query a user typed in the debugger); False: the query is trusted.
            sandboxed: check it so, and in the sandbox whether the agent has one or not
                (a query or condition a web page sent the mind inspector).
            limit: at most this many answers (the first ones); None: all of them.

        Returns:
            One mapping per answer, from each variable of ``text`` to its value (``Atom``
            for an atom, ``str`` for a string, ``Struct`` for a compound, numbers and lists
            as themselves); ``[]`` when there is none, ``[{}]`` for a yes without variables.

        Raises:
            KBError: the query is not valid Prolog or raised an error.
        """
        return self.ms.query(op, text, trusted=not (confined or sandboxed),
                             sandboxed=sandboxed, limit=limit)

    def beliefs(self) -> list[Term]:
        """The agent's beliefs (its belief base's facts), in order."""
        return self.ms.beliefs()

    def goals(self) -> list[list[Term]]:
        """The agent's goals, each as the list of its facts (``on(a,b), on(b,c)`` is one goal
        of two facts)."""
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
        event = dataclasses.replace(readable(event), cycle=self.cycle)
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
                shown = cause_traceback(err)
                if shown is not None:
                    self.log(shown)
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
            running = self.focus[-1].module.name if self.focus else "main"
            self.warn(f"{goal_origin(self.program, self.ms, running, facts)}: checking whether "
                      f"goal {goal_text(facts)} is achieved {why}; the goal is kept")
