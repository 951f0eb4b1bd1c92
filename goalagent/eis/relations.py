"""Entities, registered agents and which agent perceives and acts through which entity, with
the environment listeners told of entities appearing, freed and deleted: the bookkeeping
base of :class:`~goalagent.eis.interface.Environment`.

The relation is kept both ways (agent -> its entities, entity -> its agents), and the agents
left without an entity in a heap by registration order, so that asking who holds an entity
or which agent waits first for one costs no scan of all agents: a system launching an agent
on each of 100,000 entities stays O(N) (issue 29).
"""

from __future__ import annotations

import heapq
from itertools import count
from typing import ClassVar

from goalagent.eis.exceptions import (
    AgentException,
    EntityException,
    EnvironmentInterfaceException,
    RelationException,
)

__all__ = ["EntityRelations", "tell"]


def tell(listener: object, method: str, *args: object) -> None:
    """Call ``listener.method(*args)`` when the listener has that method (Protocols are loose)."""
    handler = getattr(listener, method, None)
    if handler is not None:
        handler(*args)


class EntityRelations:
    """Entities (name -> type, in the order they appeared), agents (name -> associated
    entities, in registration order) and the listeners of both."""

    name: ClassVar[str]  # the environment's name, for messages

    def __init__(self) -> None:
        self._entities: dict[str, str] = {}
        self._agents: dict[str, list[str]] = {}
        self._holders: dict[str, dict[str, None]] = {}  # entity -> its agents (a set in order)
        self._rank: dict[str, int] = {}  # agent -> when it was registered
        self._ranks = count()
        # (rank, agent) of agents that were left without an entity, some since given one or
        # unregistered: checked when read (first_agent_without_entity).
        self._waiting: list[tuple[int, str]] = []
        self._env_listeners: list[object] = []
        self._agent_listeners: dict[str, list[object]] = {}

    # ---- entities ---------------------------------------------------------------------------

    def entities(self) -> list[str]:
        """All entities, in the order they appeared."""
        return list(self._entities)

    def entity_type(self, entity: str) -> str:
        """The type of ``entity``."""
        self._require_entity(entity, EntityException)
        return self._entities[entity]

    def _require_entity(self, entity: str, error: type[EnvironmentInterfaceException]) -> None:
        if entity not in self._entities:
            known = ", ".join(self._entities) or "none"
            raise error(
                f"environment '{self.name}' has no entity '{entity}' (entities: {known})"
            )

    def _require_agent(self, agent: str, error: type[EnvironmentInterfaceException]) -> None:
        if agent not in self._agents:
            raise error(f"agent '{agent}' is not registered with environment '{self.name}'")

    def add_entity(self, entity: str, type: str = "entity") -> None:
        """Add a new entity of ``type`` and tell the environment listeners."""
        if entity in self._entities:
            raise EntityException(f"environment '{self.name}' already has entity '{entity}'")
        self._entities[entity] = type
        self._holders[entity] = {}
        for listener in list(self._env_listeners):
            tell(listener, "handle_new_entity", entity, type)

    def delete_entity(self, entity: str) -> None:
        """Remove ``entity`` and its associations, and tell the listeners which agents had it."""
        self._require_entity(entity, EntityException)
        agents = self._drop_associations(entity)
        del self._entities[entity]
        del self._holders[entity]
        for listener in list(self._env_listeners):
            tell(listener, "handle_deleted_entity", entity, agents)

    def free_entity(self, entity: str) -> None:
        """Dissociate every agent from ``entity`` and tell the listeners which agents had it."""
        self._require_entity(entity, EntityException)
        agents = self._drop_associations(entity)
        if not agents:
            raise RelationException(f"entity '{entity}' is not associated with any agent")
        self._notify_free(entity, agents)

    def _drop_associations(self, entity: str) -> list[str]:
        agents = self.associated_agents(entity)
        for agent in agents:
            self._dissociate(agent, entity)
        return agents

    def _dissociate(self, agent: str, entity: str) -> None:
        """Drops the pair both ways; an agent left without entities waits for one."""
        entities = self._agents[agent]
        entities.remove(entity)
        del self._holders[entity][agent]
        if not entities:
            heapq.heappush(self._waiting, (self._rank[agent], agent))

    def _notify_free(self, entity: str, agents: list[str]) -> None:
        for listener in list(self._env_listeners):
            tell(listener, "handle_free_entity", entity, agents)

    # ---- agents -------------------------------------------------------------------------------

    def agents(self) -> list[str]:
        """All registered agents, in registration order."""
        return list(self._agents)

    def register_agent(self, agent: str) -> None:
        """Register ``agent`` so it can be associated with entities."""
        if agent in self._agents:
            raise AgentException(
                f"agent '{agent}' is already registered with environment '{self.name}'"
            )
        self._agents[agent] = []
        self._rank[agent] = rank = next(self._ranks)
        heapq.heappush(self._waiting, (rank, agent))

    def unregister_agent(self, agent: str) -> None:
        """Unregister ``agent``, freeing its entities and dropping its listeners."""
        self._require_agent(agent, AgentException)
        self.free_agent(agent)
        del self._agents[agent]
        del self._rank[agent]
        self._agent_listeners.pop(agent, None)

    def associate_entity(self, agent: str, entity: str) -> None:
        """Let ``agent`` perceive and act through ``entity`` (an entity may have several agents)."""
        self._require_agent(agent, RelationException)
        self._require_entity(entity, RelationException)
        if entity in self._agents[agent]:
            raise RelationException(f"agent '{agent}' is already associated with '{entity}'")
        self._agents[agent].append(entity)
        self._holders[entity][agent] = None

    def free_agent(self, agent: str) -> None:
        """Dissociate ``agent`` from all its entities; entities left without agents are freed."""
        self._require_agent(agent, RelationException)
        for entity in list(self._agents[agent]):
            self.free_pair(agent, entity)

    def free_pair(self, agent: str, entity: str) -> None:
        """Dissociate ``agent`` from ``entity``; tell the listeners if the entity is now free."""
        self._require_agent(agent, RelationException)
        self._require_entity(entity, RelationException)
        if entity not in self._agents[agent]:
            raise RelationException(f"agent '{agent}' is not associated with '{entity}'")
        self._dissociate(agent, entity)
        if not self._holders[entity]:
            self._notify_free(entity, [agent])

    def associated_entities(self, agent: str) -> list[str]:
        """The entities ``agent`` is associated with, in association order."""
        self._require_agent(agent, AgentException)
        return list(self._agents[agent])

    def associated_agents(self, entity: str) -> list[str]:
        """The agents associated with ``entity``, in registration order."""
        self._require_entity(entity, EntityException)
        return sorted(self._holders[entity], key=self._rank.__getitem__)

    def is_free(self, entity: str) -> bool:
        """Whether ``entity`` exists and no agent is associated with it."""
        return not self._holders.get(entity, True)

    def free_entities(self) -> list[str]:
        """Entities no agent is associated with."""
        return [entity for entity, agents in self._holders.items() if not agents]

    def first_agent_without_entity(self) -> str | None:
        """The earliest registered agent with no entity (None: every agent has one)."""
        waiting = self._waiting
        while waiting:
            rank, agent = waiting[0]
            if self._rank.get(agent) == rank and not self._agents[agent]:
                return agent
            heapq.heappop(waiting)
        return None

    def _targets(
        self, agent: str, entities: tuple[str, ...], error: type[EnvironmentInterfaceException]
    ) -> list[str]:
        """The entities ``agent`` addresses: the given ones (checked) or all its associated."""
        self._require_agent(agent, error)
        if not entities:
            return list(self._agents[agent])
        for entity in entities:
            self._require_entity(entity, error)
            if entity not in self._agents[agent]:
                raise error(f"agent '{agent}' is not associated with entity '{entity}'")
        return list(entities)
