"""The reasoning cycle: one agent, its mental state in SWI-Prolog, its modules and actions.

Each cycle: collect percepts and messages -> (init module, first cycle only) -> event
module -> main module (or the module in focus) -> blind commitment. The modules of a cycle
run in one call of the rule interpreter (see ``goalagent.agent.rules``); GOAL's semantics
are in docs/goal-language.md. Environments and other agents are reached through
``AgentIO`` and ``Postman``, so the agent knows nothing of EIS or scheduling.
"""

from __future__ import annotations

import random
import sys
from collections.abc import Callable
from pathlib import Path
from typing import TextIO

from goalagent import ast
from goalagent.agent.actions import AgentIO
from goalagent.agent.checks import update_formulas, validate_program
from goalagent.agent.errors import AgentError
from goalagent.agent.events import Tracer, goal_event, plain_variables
from goalagent.agent.idleness import IDLE_WARNING_CYCLES, note_idleness
from goalagent.agent.messages import Postman
from goalagent.agent.modules import Focus, leave_focus
from goalagent.agent.perception import perceive
from goalagent.agent.problems import goal_origin, goal_text, module_of
from goalagent.agent.reports import CycleReport, RunResult
from goalagent.agent.rules import RuleApplication
from goalagent.agent.timers import Timer
from goalagent.agent.view import AgentView
from goalagent.events import EventKind
from goalagent.kb.engine import KBError, get_engine
from goalagent.kb.limits import Limits
from goalagent.kb.mentalstate import MentalState
from goalagent.kb.terms import Term
from goalagent.parser import parse_agent, parse_agent_file

Bindings = dict[str, Term]


class Agent(AgentView):
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
        super().__init__(name or program.name, tracer=tracer, warn=warn)
        self.io = io
        self.postman = postman
        self.random = random.Random(seed)
        get_engine().seed_random(seed)  # Prolog's random/1, random_float, roulette choices
        self.output = output or sys.stdout
        self.terminated = False
        self.total_actions = 0
        self.last_report: CycleReport | None = None
        self.focus: list[Focus] = []  # user modules the agent stays in, innermost last
        self.timers: dict[str, Timer] = {}  # GOAL 7's running timers, by name
        self.idle_warning = idle_warning
        self.idle_cycles = 0  # cycles in a row without action, new percept or message
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
            perceive(self)  # (without them, no percepts and no messages: nothing to do)
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
        note_idleness(self)
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
            perceive(self)
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
            perceive(self)
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

    # ------------------------------------------------------------------ cycle parts
    def _check_main_exit(self, exit_option: str) -> None:
        """The main module's exit option (nogoals, noaction, always) after its pass."""
        if exit_option == "nogoals" and not self.ms.goals():
            self.terminated = True
        elif exit_option == "noaction" and not self.report.acted:
            self.terminated = True
        elif exit_option == "always":
            self.terminated = True

    def _blind_commitment(self) -> None:
        for goal in self.ms.blind_commitment():
            if self.listeners:
                self.tell(goal_event(self.name, EventKind.GOAL_ACHIEVED, goal))
        for facts, why in self.ms.take_unchecked():
            running = self.focus[-1].module.name if self.focus else "main"
            self.warn(f"{goal_origin(self.program, self.ms, running, facts)}: checking whether "
                      f"goal {goal_text(facts)} is achieved {why}; the goal is kept")
