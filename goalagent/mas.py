"""Multi-agent systems: launching agents on an EIS environment, messaging and scheduling.

A single `.goal` file run from the CLI is a system of one agent, so there is one mechanism:
``MultiAgentSystem``. Agents take turns one cycle each, in launch order; an agent that
terminates or fails is reported and the others go on. How a system is made from files or
text is goalagent.mas_building's job, its side facing the environment
goalagent.mas_environment's.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TextIO

from goalagent import ast
from goalagent.agent import Agent, AgentError, Listener, LocalPostman, Tracer
from goalagent.eis.exceptions import EnvironmentInterfaceException
from goalagent.eis.interface import Environment, EnvironmentState
from goalagent.eis.terms import Parameter, from_term
from goalagent.kb.engine import KBError
from goalagent.kb.identity import AgentDirectory
from goalagent.kb.limits import Limits
from goalagent.kb.terms import Term
from goalagent.mas_building import (
    ParameterText,
    SystemBuilding,
    looks_like_file_name,
    parse_parameter,
    read_parameter,
)
from goalagent.mas_capacity import agent_capacity, capacity_message
from goalagent.mas_environment import EntityIO, EntityLaunches
from goalagent.parser import GoalSyntaxError

__all__ = ["AgentSummary", "MultiAgentSystem", "ParameterText", "looks_like_file_name",
           "parse_parameter", "read_parameter"]


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


class MultiAgentSystem(EntityLaunches, SystemBuilding):
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

    # ------------------------------------------------------------------ launching
    def capacity(self) -> tuple[int, bool]:
        """How many agents this system may hold (``max_agents``, or what the memory available
        when first asked allows: goalagent.mas_capacity), and whether it was set by hand."""
        if self._max_agents is None:
            self._max_agents = agent_capacity()
            self._capacity_by_hand = False
        return self._max_agents, self._capacity_by_hand

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

