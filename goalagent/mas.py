"""Multi-agent systems: launching agents on an EIS environment, messaging and scheduling.

A single `.goal` file run from the CLI is a system of one agent, so there is one mechanism:
``MultiAgentSystem``. Agents take turns one cycle each, in launch order; an agent that
terminates or fails is reported and the others go on.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, TextIO

from goalagent import ast
from goalagent.agent import Agent, AgentError, Listener, LocalPostman, Tracer
from goalagent.eis.exceptions import EnvironmentInterfaceException
from goalagent.eis.interface import Environment, EnvironmentState
from goalagent.eis.terms import (
    Parameter,
    from_term,
)
from goalagent.kb.engine import KBError, PrologSyntaxError, get_engine
from goalagent.kb.identity import AgentDirectory
from goalagent.kb.limits import Limits
from goalagent.kb.terms import Atom, Term, Var
from goalagent.mas_capacity import agent_capacity, capacity_message, check_launches
from goalagent.mas_environment import EntityIO, EntityLaunches, make_environment
from goalagent.parser import (
    GoalSyntaxError,
    load_agents,
    parse_agent,
    parse_agent_file,
    parse_mas_file,
)


@dataclass(frozen=True)
class AgentSummary:
    """One line of the end-of-run report."""

    name: str
    cycles: int
    actions: int
    goals_left: int
    status: str

    def __str__(self) -> str:
        return (f"{self.name}: {self.status} after {self.cycles} cycles, {self.actions} actions, "
                f"{self.goals_left} goals left")


def parse_parameter(text: str) -> Term:
    """An environment parameter value given as Prolog text (``--env-param k=v``); text that
    is not a Prolog term, or is a lone variable (``map=Banana``), is taken as an atom, so
    paths and capitalised names need no quotes."""
    try:
        term = get_engine().parse_term(text)
    except PrologSyntaxError:
        return Atom(text)
    return Atom(text.strip()) if isinstance(term, Var) else term


@dataclass(frozen=True)
class ParameterText:
    """An environment parameter's value as the user typed it (``--env-param k=v``), read once
    the environment is known: a parameter it declares as a path takes a file name as written
    (see ``read_parameter``)."""

    text: str


def looks_like_file_name(text: str) -> bool:
    """Unquoted text with a ``.`` or a ``/`` in it: ``db.json``, ``out/db``, ``../x.yaml``
    (as Prolog, ``db.json`` would be the term '.'(db, json))."""
    stripped = text.strip()
    return bool(stripped) and stripped[0] not in "'\"" and any(c in stripped for c in "./")


def read_parameter(value: Term | ParameterText, *, path: bool) -> Term:
    """The term of an init parameter's value: typed text is taken as written when the
    parameter is a path and the text looks like a file name, else read as Prolog
    (``parse_parameter``); a term is kept as it is (a ``.mas2g`` file's init values are terms
    already, so a file name there is quoted: ``objects = 'db.json'``)."""
    if not isinstance(value, ParameterText):
        return value
    if path and looks_like_file_name(value.text):
        return value.text.strip()
    return parse_parameter(value.text)


class MultiAgentSystem(EntityLaunches):
    """Agents, their environment and the message routing between them.

    Made from a ``.mas2g`` file (:meth:`from_mas_file`), or from one agent file or text on
    an environment (:meth:`for_agent_file`, :meth:`for_agent_text`); :meth:`run` runs the
    agents in turn, one cycle each, until all have stopped; :meth:`close` frees them and
    kills the environment. A single ``.goal`` file run from the command line is such a system
    of one agent.

    Args:
        environment: the environment the agents act in (None: none).
        seed: agent number i gets seed ``seed + i``.
        output: where the agents' ``print/1`` writes (default: stdout).
        tracer: called with (agent, kind, text) for every event of every agent.
        warn: called with each warning or failure line (default: printed on stderr).
        listeners: told every event of every agent (``--trace``, the inspector).
        limits: each agent's bounds (default ``Limits()``), unless its agent file sets its
            own.
        max_agents: how many agents it may hold (``--max-agents``; None: as many as the
            memory available holds, goalagent.mas_capacity); a launch past it is refused.

    Attributes:
        agents: the agents launched so far, in launch order (``system.agents[0]`` is the
            agent of :meth:`for_agent_file` and :meth:`for_agent_text`). Entity-launched
            agents join when the environment offers their entity.
        environment: the environment, or None.
        failures: agent name -> why it failed, for the agents stopped by an error.
    """

    def __init__(
        self,
        environment: Environment | None = None,
        *,
        seed: int = 0,
        output: TextIO | None = None,
        tracer: Tracer | None = None,
        warn: Callable[[str], None] | None = None,
        listeners: Sequence[Listener] = (),
        limits: Limits | None = None,
        max_agents: int | None = None,
    ) -> None:
        self.environment = environment
        self._max_agents = max_agents  # (None: measured when first asked)
        self._capacity_by_hand = max_agents is not None
        self.limits = limits or Limits()  # each agent's, unless its agent file says more
        self._agent_limits: dict[str, Limits] = {}  # agent file name -> its agents' limits
        self.seed = seed
        self.output = output or sys.stdout
        self.tracer = tracer
        self.listeners = list(listeners)  # told every event of every agent (--trace, inspector)
        self.warn = warn or (lambda message: print(message, file=sys.stderr))
        self.postman = LocalPostman()
        self._directory = AgentDirectory()  # agent/1 of every member, stored once
        self.agents: list[Agent] = []
        self._names: set[str] = set()  # the agents' names: a launch checks one in O(1)
        self.current: Agent | None = None  # the agent whose cycle is running
        self.interrupted = False  # a signal stopped the run
        self.failures: dict[str, str] = {}
        self._programs: dict[str, ast.AgentProgram] = {}
        self._entity_launches: list[ast.LaunchRule] = []
        self._launched_per_rule: dict[int, int] = {}

    # ------------------------------------------------------------------ building
    @classmethod
    def from_mas_file(
        cls,
        path: str | Path,
        *,
        env_params: Mapping[str, Term | ParameterText] | None = None,
        seed: int = 0,
        output: TextIO | None = None,
        tracer: Tracer | None = None,
        warn: Callable[[str], None] | None = None,
        listeners: Sequence[Listener] = (),
        limits: Limits | None = None,
        max_agents: int | None = None,
    ) -> MultiAgentSystem:
        """Parse a ``.mas2g`` file (any GOAL version), start its environment and launch its
        agents (GOAL 4/5 agent files or GOAL 6+ agent definitions).

        Args:
            path: the system file.
            env_params: init parameters that replace or add to the file's
                (``--env-param``), as terms (``parse_parameter("[0,0,0]")``) or as typed
                text (``ParameterText("db.json")``: a file name where the environment
                declares a path).
            seed: agent number i gets seed ``seed + i``.
            output: where the agents' ``print/1`` writes (default: stdout).
            tracer: called with (agent, kind, text) for every event of every agent.
            warn: called with each warning or failure line (default: printed on stderr).
            listeners: told every event of every agent.
            limits: each agent's bounds (default ``Limits()``).
            max_agents: how many agents it may hold (None: what the memory available holds);
                a file launching more is refused before any agent is built.

        Returns:
            The system, its environment started, before any agent's first cycle.

        Raises:
            GoalSyntaxError: a file is malformed or names what does not exist.
            AgentError: an agent's program cannot be loaded.
            EnvironmentInterfaceException: the environment refused its init parameters.
        """
        mas = parse_mas_file(path)
        programs = load_agents(mas)
        numbers = {agentfile.name: agentfile.number for agentfile in mas.agentfiles}
        params: dict[str, Term | ParameterText] = {
            key: get_engine().parse_term(value.text) for key, value in mas.env_init}
        params.update(env_params or {})
        environment = (make_environment(mas.environment, mas.env_pos or mas.pos)
                       if mas.environment else None)
        if environment is not None:
            environment.home = Path(path).parent
        system = cls(environment, seed=seed, output=output, tracer=tracer, warn=warn,
                     listeners=listeners, limits=limits, max_agents=max_agents)
        system._programs.update(programs)
        check_launches(mas, numbers, *system.capacity())
        for agentfile in mas.agentfiles:
            if agentfile.limits:
                system._agent_limits[agentfile.name] = system._limits_for(dict(agentfile.limits))
        for rule in mas.launches:
            if rule.on_entity:
                system._entity_launches.append(rule)
            else:
                number = rule.number if rule.number != 1 else numbers.get(rule.agentfile, 1)
                for index in range(number):
                    name = rule.agent_name if number == 1 else f"{rule.agent_name}{index + 1}"
                    system.launch(name, programs[rule.agentfile],
                                  limits=system._agent_limits.get(rule.agentfile))
        if not mas.launches:
            for name, program in programs.items():
                number = numbers.get(name, 1)
                for index in range(number):
                    system.launch(name if number == 1 else f"{name}{index + 1}", program,
                                  limits=system._agent_limits.get(name))
        system._start_environment(params)
        return system

    @classmethod
    def for_agent_file(
        cls,
        path: str | Path,
        *,
        environment: str | None = None,
        env_params: Mapping[str, Term | ParameterText] | None = None,
        seed: int = 0,
        output: TextIO | None = None,
        tracer: Tracer | None = None,
        warn: Callable[[str], None] | None = None,
        listeners: Sequence[Listener] = (),
        limits: Limits | None = None,
        max_agents: int | None = None,
    ) -> MultiAgentSystem:
        """A system of the one agent in a ``.goal`` file, on ``environment`` if given (as
        ``goalagent run FILE --env NAME`` makes it).

        Args:
            path: the agent file.
            environment: a registered environment name (``blocksworld``) or
                ``package.module:Class``; None: no environment.
            env_params: the environment's init parameters, as terms or typed text
                (``ParameterText``).
            seed: agent number i gets seed ``seed + i``.
            output: where the agents' ``print/1`` writes (default: stdout).
            tracer: called with (agent, kind, text) for every event of every agent.
            warn: called with each warning or failure line (default: printed on stderr).
            listeners: told every event of every agent.
            limits: each agent's bounds (default ``Limits()``).
            max_agents: how many agents it may hold (None: what the memory available holds).

        Returns:
            The system; its agent is ``system.agents[0]``.
        """
        program = parse_agent_file(path)
        return cls._of_one(program, ast.Pos(str(path), 1, 1), Path(path).parent, environment,
                           env_params, dict(seed=seed, output=output, tracer=tracer,
                                            warn=warn, listeners=listeners, limits=limits,
                                            max_agents=max_agents))

    @classmethod
    def for_agent_text(
        cls,
        text: str,
        *,
        file: str = "<string>",
        environment: str | None = None,
        env_params: Mapping[str, Term | ParameterText] | None = None,
        seed: int = 0,
        output: TextIO | None = None,
        tracer: Tracer | None = None,
        warn: Callable[[str], None] | None = None,
        listeners: Sequence[Listener] = (),
        limits: Limits | None = None,
    ) -> MultiAgentSystem:
        """A system of one agent given as program text, on ``environment`` if given: the way
        to put an agent made from a string in an environment (step it as
        ``system.agents[0].step()``).

        Args:
            text: the agent program (the single-file ``.goal`` format).
            file: the name its errors and positions give.
            environment: a registered environment name or ``package.module:Class``.
            env_params: the environment's init parameters, as terms or typed text
                (``ParameterText``).
            seed: agent number i gets seed ``seed + i``.
            output: where the agents' ``print/1`` writes (default: stdout).
            tracer: called with (agent, kind, text) for every event of every agent.
            warn: called with each warning or failure line (default: printed on stderr).
            listeners: told every event of every agent.
            limits: each agent's bounds (default ``Limits()``).

        Returns:
            The system; its agent is ``system.agents[0]``.
        """
        program = parse_agent(text, file)
        return cls._of_one(program, ast.Pos(file, 1, 1), None, environment, env_params,
                           dict(seed=seed, output=output, tracer=tracer, warn=warn,
                                listeners=listeners, limits=limits))

    @classmethod
    def _of_one(cls, program: ast.AgentProgram, pos: ast.Pos, home: Path | None,
                environment: str | None, env_params: Mapping[str, Term | ParameterText] | None,
                options: dict[str, Any]) -> MultiAgentSystem:
        """The system of one program on ``environment`` (files it names looked for in
        ``home``)."""
        env = make_environment(environment, pos) if environment else None
        if env is not None:
            env.home = home
        system = cls(env, **options)
        system.launch(program.name, program)
        system._start_environment(dict(env_params or {}))
        return system

    def capacity(self) -> tuple[int, bool]:
        """How many agents this system may hold (``max_agents``, or what the memory available
        when first asked allows: goalagent.mas_capacity), and whether it was set by hand."""
        if self._max_agents is None:
            self._max_agents = agent_capacity()
            self._capacity_by_hand = False
        return self._max_agents, self._capacity_by_hand

    def _limits_for(self, options: dict[str, object]) -> Limits:
        """The run's limits with an agent file's own (a sandbox stays a sandbox)."""
        options["sandbox"] = bool(options.get("sandbox")) or self.limits.sandbox
        return replace(self.limits, **options)  # type: ignore[arg-type]

    def launch(self, name: str, program: ast.AgentProgram, entity: str | None = None, *,
               limits: Limits | None = None) -> Agent:
        """Create an agent (bounded by ``limits``, default the system's), register it for
        messages and (if any) with the environment. A name already taken is made unique as
        GOAL's runtime does, numbering the later ones: the first of ``name2``, ``name3``, ...
        that is free (as entity launches number theirs). One more agent than the system
        may hold (``capacity``) is an AgentError."""
        limit, by_hand = self.capacity()
        if len(self.agents) >= limit:
            raise AgentError(capacity_message(len(self.agents) + 1, limit, by_hand=by_hand))
        name = self._unique_name(name)
        io = None
        if self.environment is not None:
            self.environment.register_agent(name)
            if entity is not None:
                self.environment.associate_entity(name, entity)
            io = EntityIO(self.environment, name)
        self.postman.register(name)
        try:
            agent = Agent(program, name=name, io=io, postman=self.postman,
                          seed=self.seed + len(self.agents), output=self.output,
                          tracer=self.tracer, warn=self.warn, limits=limits or self.limits)
        except BaseException:  # no member: the environment forgets it (it waits for no body)
            if self.environment is not None:
                self.environment.unregister_agent(name)
            raise
        for listener in self.listeners:
            agent.listen(listener)
        self.agents.append(agent)
        self._names.add(name)
        self._directory.add(name)
        agent.ms.join(name, self._directory)
        return agent

    def _unique_name(self, name: str) -> str:
        taken = self._names
        if name not in taken:
            return name
        return next(f"{name}{n}" for n in range(2, len(taken) + 3) if f"{name}{n}" not in taken)

    def _start_environment(self, params: dict[str, Term | ParameterText]) -> None:
        if self.environment is None:
            return
        self.environment.attach_environment_listener(self)
        environment = self.environment
        converted: dict[str, Parameter] = {
            key: from_term(read_parameter(value, path=environment.is_path_parameter(key)))
            for key, value in params.items()}
        self.environment.init(converted)
        self.environment.start()
        for entity in self.environment.free_entities():
            self.handle_new_entity(entity, self.environment.entity_type(entity))

    # ------------------------------------------------------------------ running
    def run(self, max_cycles: int | None = None,
            after_cycle: Callable[[Agent], None] | None = None) -> list[AgentSummary]:
        """Round-robin, one cycle per agent per turn, until all stop or ``max_cycles``;
        ``after_cycle`` is called with each agent after each of its cycles."""
        while True:
            live = [a for a in self.agents if not a.terminated and a.name not in self.failures
                    and (max_cycles is None or a.cycle < max_cycles)]
            if not live:
                break
            for agent in live:
                self.step(agent)
                if after_cycle is not None:
                    after_cycle(agent)
        return self.summaries()

    def step(self, agent: Agent, cycle: Callable[[], object] | None = None) -> None:
        """One cycle of ``agent`` (``cycle``: what to run instead of ``agent.step``, a test's
        step); whatever it raises (an error of its program, of the
        environment serving it, or of Python while serving it, e.g. a recursion too deep)
        is that agent's failure: it is reported and stopped, the others go on."""
        self.current = agent  # left set when a signal stops the run: it says where
        try:
            (cycle or agent.step)()
        except (AgentError, KBError, GoalSyntaxError, EnvironmentInterfaceException) as err:
            self._fail(agent, str(err))
        except Exception as err:  # noqa: BLE001 - one agent's failure is never the system's
            self._fail(agent, f"{type(err).__name__}: {err}")
        self.current = None

    def _fail(self, agent: Agent, message: str) -> None:
        """Stops ``agent`` and reports why."""
        self.failures[agent.name] = message
        self.warn(f"error: agent {agent.name} failed: {message}")

    def summaries(self) -> list[AgentSummary]:
        result = []
        for agent in self.agents:
            if agent.name in self.failures:
                status = "failed"
            elif agent.terminated:
                status = "terminated"
            elif self.interrupted:
                status = "interrupted"
            else:
                status = "stopped at the cycle limit"
            result.append(AgentSummary(agent.name, agent.cycle, agent.total_actions,
                                       agent.ms.goal_count(), status))
        return result

    def close(self) -> None:
        """Kill the environment and free the agents' Prolog modules."""
        if self.environment is not None and self.environment.state is not EnvironmentState.KILLED:
            self.environment.kill()
        for agent in self.agents:
            agent.close()
        self._directory.close()

