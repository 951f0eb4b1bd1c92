"""A multi-agent system's side facing its EIS environment: each agent's connection to its
entities (``EntityIO``) and the launches the environment's entities trigger
(``EntityLaunches``: the environment listener a ``MultiAgentSystem`` is). Split from
``goalagent.mas``, which builds, schedules and closes the system.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from goalagent import ast
from goalagent.agent import ActionFailed, Agent
from goalagent.eis.exceptions import ActException, ActExceptionKind, EnvironmentInterfaceException
from goalagent.eis.interface import Environment, EnvironmentState
from goalagent.eis.registry import load_environment
from goalagent.eis.terms import Percept, action_from_term, percept_to_term
from goalagent.kb.limits import Limits
from goalagent.kb.terms import Atom, Struct, Term
from goalagent.parser import GoalSyntaxError

_CANNOT_TAKE = frozenset({ActExceptionKind.UNKNOWN_ACTION, ActExceptionKind.WRONG_PARAMETERS,
                          ActExceptionKind.NOT_REGISTERED, ActExceptionKind.WRONG_ENTITY,
                          ActExceptionKind.NO_ENTITIES})
"""Why an environment cannot take an action at all: GOAL's runtime stops the agent then
(``RunState.doPerformAction``); a refusal or failure is a warning and the agent goes on."""


class EntityIO:
    """Connects one agent to its entities in an EIS environment (``agent.AgentIO``): the
    percepts of a cycle are those of its entities plus any the environment pushed since."""

    def __init__(self, environment: Environment, agent: str) -> None:
        self.environment = environment
        self.agent = agent
        self._pushed: list[Percept] = []
        environment.attach_agent_listener(agent, self)

    def handle_percept(self, agent: str, percept: Percept) -> None:
        """EIS agent listener: keep a pushed percept for the agent's next cycle."""
        self._pushed.append(percept)

    def percepts(self) -> list[Term]:
        pushed, self._pushed = self._pushed, []
        if not self.environment.associated_entities(self.agent):
            return [percept_to_term(p) for p in pushed]
        try:
            per_entity = self.environment.get_all_percepts(self.agent)
        except EnvironmentInterfaceException as err:
            raise ActionFailed(str(err)) from err
        current = [p for percepts in per_entity.values() for p in percepts]
        return [percept_to_term(p) for p in current + pushed]

    def act(self, action: Struct | Atom) -> None:
        try:
            self.environment.perform_action(self.agent, action_from_term(action))
        except EnvironmentInterfaceException as err:
            fatal = isinstance(err, ActException) and err.kind in _CANNOT_TAKE
            raise ActionFailed(str(err), fatal=fatal) from err


class EntityLaunches:
    """The EIS environment listener of a system: agents launched on the entities the
    environment offers (the ``.mas2g``'s launch rules), or entities given to agents waiting
    for one."""

    environment: Environment | None
    agents: list[Agent]
    _names: set[str]
    _programs: dict[str, ast.AgentProgram]
    _agent_limits: dict[str, Limits]
    _entity_launches: list[ast.LaunchRule]
    _launched_per_rule: dict[int, int]

    if TYPE_CHECKING:  # MultiAgentSystem.launch
        def launch(self, name: str, program: ast.AgentProgram, entity: str | None = None, *,
                   limits: Limits | None = None) -> Agent: ...

    def handle_new_entity(self, entity: str, type: str) -> None:
        """Launch rules ``when [type=T, max=N]@env do launch ...`` / ``when type = T launch
        a, b.`` (the first rule whose entity condition fits and that may still launch: all
        its agents on this entity) and plain agents waiting for a body: the first agent
        without an entity gets this one. O(1) in the number of agents and entities (but
        for the rules), so launching N is O(N)."""
        environment = self.environment
        if environment is None or not environment.is_free(entity):
            return
        groups: dict[int, list[int]] = {}
        for index, rule in enumerate(self._entity_launches):
            groups.setdefault(rule.group, []).append(index)
        for indices in groups.values():
            first = self._entity_launches[indices[0]]
            if first.entity_type not in (None, type) or first.entity_name not in (None, entity):
                continue
            ready = [index for index in indices
                     if (most := self._entity_launches[index].max) is None
                     or self._launched_per_rule.get(index, 0) < most]
            if not ready:
                continue
            for index in ready:
                rule = self._entity_launches[index]
                launched = self._launched_per_rule.get(index, 0)
                self._launched_per_rule[index] = launched + 1
                name = entity if rule.agent_name == "*" else rule.agent_name
                if name in self._names:
                    name = f"{name}{launched + 1}"
                self.launch(name, self._programs[rule.agentfile], entity,
                            limits=self._agent_limits.get(rule.agentfile))
            return
        waiting = environment.first_agent_without_entity()  # (the agents in launch order)
        if waiting is not None:
            environment.associate_entity(waiting, entity)

    def handle_state_change(self, state: EnvironmentState) -> None:
        """Environment state changes need no action from the scheduler."""

    def handle_free_entity(self, entity: str, agents: list[str]) -> None:
        """An entity freed by its agents waits for an agent to ask for it: nothing to do."""

    def handle_deleted_entity(self, entity: str, agents: list[str]) -> None:
        """An entity that left takes its percepts with it: nothing to do (its agents run on
        without a body, as in GOAL)."""



def make_environment(spec: str, pos: ast.Pos) -> Environment:
    """The environment ``spec`` names, made; one that cannot be made is an error at ``pos``."""
    try:
        return load_environment(spec)()
    except EnvironmentInterfaceException as err:
        raise GoalSyntaxError.at(pos, str(err)) from None
