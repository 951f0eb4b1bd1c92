"""How a multi-agent system is made: from a ``.mas2g`` file (its environment, agent files
and launch policy), or from one agent file or text on an environment, and how the
environment's init parameters typed by a user are read. Split from ``goalagent.mas``, which
launches, runs and closes the system; ``MultiAgentSystem`` takes these builders from
:class:`SystemBuilding`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, TextIO, TypeVar

from goalagent import ast
from goalagent.agent import Agent, Listener, Tracer
from goalagent.eis.interface import Environment
from goalagent.kb.engine import PrologSyntaxError, get_engine
from goalagent.kb.limits import Limits
from goalagent.kb.terms import Atom, Term, Var
from goalagent.mas_capacity import check_launches
from goalagent.mas_environment import make_environment
from goalagent.parser import load_agents, parse_agent, parse_agent_file, parse_mas_file

__all__ = ["ParameterText", "SystemBuilding", "looks_like_file_name", "parse_parameter",
           "read_parameter"]

_System = TypeVar("_System", bound="SystemBuilding")


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


class SystemBuilding:
    """The ways to make a system (``MultiAgentSystem`` is one): each builds it, launches its
    agents and starts its environment."""

    environment: Environment | None
    limits: Limits
    _programs: dict[str, ast.AgentProgram]
    _agent_limits: dict[str, Limits]
    _entity_launches: list[ast.LaunchRule]

    if TYPE_CHECKING:  # MultiAgentSystem's
        def __init__(self, environment: Environment | None = None, *, seed: int = 0,
                     output: TextIO | None = None, tracer: Tracer | None = None,
                     warn: Callable[[str], None] | None = None,
                     listeners: Sequence[Listener] = (), limits: Limits | None = None,
                     max_agents: int | None = None) -> None: ...

        def capacity(self) -> tuple[int, bool]: ...

        def launch(self, name: str, program: ast.AgentProgram, entity: str | None = None, *,
                   limits: Limits | None = None) -> Agent: ...

        def _start_environment(self, params: dict[str, Term | ParameterText]) -> None: ...

    @classmethod
    def from_mas_file(
        cls: type[_System],
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
    ) -> _System:
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
        environment = None
        if mas.environment:
            environment = make_environment(mas.environment, mas.env_pos or mas.pos)
            environment.home = Path(path).parent
            if mas.environment.lower().endswith(".jar"):
                environment.jar = environment.home / mas.environment
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
        cls: type[_System],
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
    ) -> _System:
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
        cls: type[_System],
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
    ) -> _System:
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
    def _of_one(cls: type[_System], program: ast.AgentProgram, pos: ast.Pos, home: Path | None,
                environment: str | None, env_params: Mapping[str, Term | ParameterText] | None,
                options: dict[str, Any]) -> _System:
        """The system of one program on ``environment`` (files it names looked for in
        ``home``)."""
        env = make_environment(environment, pos) if environment else None
        if env is not None:
            env.home = home
        system = cls(env, **options)
        system.launch(program.name, program)
        system._start_environment(dict(env_params or {}))
        return system

    def _limits_for(self, options: dict[str, object]) -> Limits:
        """The run's limits with an agent file's own (a sandbox stays a sandbox)."""
        options["sandbox"] = bool(options.get("sandbox")) or self.limits.sandbox
        return replace(self.limits, **options)  # type: ignore[arg-type]
