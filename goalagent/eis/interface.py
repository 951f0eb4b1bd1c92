"""The Environment base class, after the Java Environment Interface Standard used by GOAL.

An environment holds *entities* (things an agent can control, each with a type) and knows which
registered *agents* are associated with which entities. Agents perceive through their entities
(``get_all_percepts``) and act through them (``perform_action``). Listeners hear about state
changes, entities appearing, being freed or deleted, and percepts the environment pushes.

Subclasses implement the world in a few hooks: ``do_init``, ``do_start``, ``do_pause``,
``do_kill``, ``do_reset``, ``percepts_for_entity`` and ``perform_entity_action``; the base class
does the bookkeeping and checking (entities and agents in relations.py, its base).
Everything runs on the caller's thread (pyswip is not thread-safe, so environments must not
call listeners from other threads).
"""

from __future__ import annotations

from collections.abc import Mapping
from enum import Enum
from pathlib import Path
from typing import ClassVar, Protocol

from goalagent.eis.exceptions import (
    ActException,
    ActExceptionKind,
    ActionRefused,
    AgentException,
    EntityException,
    EnvironmentInterfaceException,
    ManagementException,
    NoEnvironmentException,
    PerceiveException,
    RelationException,
    TranslationException,
)
from goalagent.eis.relations import EntityRelations, tell
from goalagent.eis.terms import Action, Parameter, Percept, to_parameter

__all__ = [
    "ActException",
    "ActExceptionKind",
    "ActionRefused",
    "AgentException",
    "AgentListener",
    "EntityException",
    "Environment",
    "EnvironmentInterfaceException",
    "EnvironmentListener",
    "EnvironmentState",
    "ManagementException",
    "NoEnvironmentException",
    "PerceiveException",
    "RelationException",
]


class EnvironmentState(Enum):
    """The life cycle of an environment."""

    INITIALIZING = "initializing"
    PAUSED = "paused"
    RUNNING = "running"
    KILLED = "killed"


_S = EnvironmentState
_VALID_TRANSITIONS: dict[EnvironmentState, frozenset[EnvironmentState]] = {
    _S.INITIALIZING: frozenset({_S.PAUSED, _S.RUNNING, _S.KILLED}),
    _S.PAUSED: frozenset({_S.RUNNING, _S.KILLED}),
    _S.RUNNING: frozenset({_S.PAUSED, _S.KILLED}),
    _S.KILLED: frozenset(),
}


class EnvironmentListener(Protocol):
    """Hears about an environment; any of the methods may be left out."""

    def handle_state_change(self, state: EnvironmentState) -> None:
        """The environment moved to ``state``."""

    def handle_new_entity(self, entity: str, type: str) -> None:
        """A new entity appeared (launch rules ``when entity@env`` react to this)."""

    def handle_free_entity(self, entity: str, agents: list[str]) -> None:
        """``entity`` lost its last agents ``agents`` and is free again."""

    def handle_deleted_entity(self, entity: str, agents: list[str]) -> None:
        """``entity`` left the environment; ``agents`` were associated with it."""


class AgentListener(Protocol):
    """Hears percepts the environment pushes to one agent outside the perceive step."""

    def handle_percept(self, agent: str, percept: Percept) -> None:
        """``percept`` arrived for ``agent``."""


class Environment(EntityRelations):
    """Base of all environments: state machine, entities, agents, percepts, actions, listeners."""

    name: ClassVar[str] = "environment"

    def __init__(self) -> None:
        super().__init__()
        self._state = EnvironmentState.INITIALIZING
        self.params: dict[str, Parameter] = {}
        # The folder of the program that starts the environment (a .mas2g's), where a file
        # named by an init parameter is looked for first: GOAL looks next to the
        # environment's jar, which sits beside the .mas2g. None: the working directory.
        self.home: Path | None = None
        # The environment jar a .mas2g names (resolved against its folder), where it names
        # one: the Java environment may keep its own data beside it (BW4T 2's server maps).
        self.jar: Path | None = None

    # ---- hooks for subclasses ------------------------------------------------------------

    @classmethod
    def init_parameters(cls) -> Mapping[str, str] | None:
        """The init parameters the environment takes (name -> what it does), so that a
        program's can be checked before it runs (``goalagent check``); None: not declared."""
        return None

    @classmethod
    def init_key(cls, key: str) -> str:
        """An init parameter's name as the environment reads it (some ignore case)."""
        return key

    def do_init(self, params: dict[str, Parameter]) -> None:
        """Build the world from ``params``; raise ManagementException on a bad parameter."""

    def do_start(self) -> None:
        """Let the world run (called before the state becomes RUNNING)."""

    def do_pause(self) -> None:
        """Hold the world still (called before the state becomes PAUSED)."""

    def do_kill(self) -> None:
        """Release the world's resources (called before the state becomes KILLED)."""

    def do_reset(self, params: dict[str, Parameter]) -> None:
        """Rebuild the world from the merged ``params``; by default the same as ``do_init``."""
        self.do_init(params)

    def percepts_for_entity(self, entity: str) -> list[Percept]:
        """The percepts of ``entity`` describing the current state."""
        return []

    def is_path_parameter(self, key: str) -> bool:
        """Whether init parameter ``key`` names a file, so that a value typed as a file name
        (``--env-param key=db.json``) is taken as written rather than read as a term."""
        return False

    def perform_entity_action(self, entity: str, action: Action) -> Percept | None:
        """Carry out ``action`` for ``entity``; raise ActException when it cannot be done."""
        raise ActException(
            f"environment '{self.name}' supports no actions (got {action})",
            ActExceptionKind.UNKNOWN_ACTION,
        )

    # ---- state machine ----------------------------------------------------------------------

    @property
    def state(self) -> EnvironmentState:
        """The current life-cycle state."""
        return self._state

    def _set_state(self, new: EnvironmentState) -> None:
        """Move to ``new``; staying in the same state is a no-op, an invalid move an error."""
        if new is self._state:
            return
        self._check_transition(new)
        self._state = new
        for listener in list(self._env_listeners):
            tell(listener, "handle_state_change", new)

    def _check_transition(self, new: EnvironmentState) -> None:
        """Raise ManagementException now if moving to ``new`` would be invalid."""
        if new is not self._state and new not in _VALID_TRANSITIONS[self._state]:
            hint = " (it was killed; create a new one)" if self._state is _S.KILLED else ""
            raise ManagementException(
                f"environment '{self.name}' cannot go from {self._state.value} to "
                f"{new.value}{hint}"
            )

    def _parameters(self, params: Mapping[str, object] | None) -> dict[str, Parameter]:
        """Init parameters as EIS parameters; Python shorthand values are converted."""
        result: dict[str, Parameter] = {}
        for key, value in (params or {}).items():
            try:
                result[key] = to_parameter(value)
            except TranslationException as error:
                raise ManagementException(
                    f"environment '{self.name}': init parameter '{key}': {error}"
                ) from None
        return result

    def init(self, params: Mapping[str, object] | None = None) -> None:
        """Initialise from ``params`` (once, while INITIALIZING); the state becomes PAUSED.

        Values are EIS parameters, or Python shorthand values (see ``terms.to_parameter``).
        """
        if self._state is not EnvironmentState.INITIALIZING:
            raise ManagementException(
                f"environment '{self.name}' is already initialised ({self._state.value}); "
                "use reset(params) to start over"
            )
        params = self._parameters(params)
        self.do_init(params)
        self.params = params
        self._set_state(EnvironmentState.PAUSED)

    def start(self) -> None:
        """Let the environment run (initialising it without parameters if need be): RUNNING."""
        self._check_transition(EnvironmentState.RUNNING)
        if self._state is EnvironmentState.INITIALIZING:
            self.do_init({})
            self.params = {}
        if self._state is not EnvironmentState.RUNNING:
            self.do_start()
        self._set_state(EnvironmentState.RUNNING)

    def pause(self) -> None:
        """Pause the environment (initialising it without parameters if need be): PAUSED."""
        self._check_transition(EnvironmentState.PAUSED)
        if self._state is EnvironmentState.INITIALIZING:
            self.init({})
        elif self._state is EnvironmentState.RUNNING:
            self.do_pause()
        self._set_state(EnvironmentState.PAUSED)

    def kill(self) -> None:
        """Stop the environment for good; the state becomes KILLED (killing twice is harmless)."""
        if self._state is EnvironmentState.KILLED:
            return
        try:
            if self._state is not EnvironmentState.INITIALIZING:
                self.do_kill()
        finally:
            self._set_state(EnvironmentState.KILLED)

    def reset(self, params: Mapping[str, object] | None = None) -> None:
        """Rebuild the world with the init parameters updated by ``params``; state PAUSED."""
        if self._state in (EnvironmentState.INITIALIZING, EnvironmentState.KILLED):
            raise ManagementException(
                f"environment '{self.name}' cannot be reset while {self._state.value}"
                + (" (call init(params) first)" if self._state is _S.INITIALIZING else "")
            )
        merged = {**self.params, **self._parameters(params)}
        self.do_reset(merged)
        self.params = merged
        self._set_state(EnvironmentState.PAUSED)

    # ---- listeners --------------------------------------------------------------------------

    def attach_environment_listener(self, listener: EnvironmentListener) -> None:
        """Tell ``listener`` about state changes and new, freed and deleted entities."""
        if listener not in self._env_listeners:
            self._env_listeners.append(listener)

    def detach_environment_listener(self, listener: EnvironmentListener) -> None:
        """Stop telling ``listener`` anything (unknown listeners are ignored)."""
        if listener in self._env_listeners:
            self._env_listeners.remove(listener)

    def attach_agent_listener(self, agent: str, listener: AgentListener) -> None:
        """Give ``listener`` the percepts pushed to ``agent``."""
        self._require_agent(agent, AgentException)
        listeners = self._agent_listeners.setdefault(agent, [])
        if listener not in listeners:
            listeners.append(listener)

    def detach_agent_listener(self, agent: str, listener: AgentListener) -> None:
        """Stop giving ``listener`` the percepts pushed to ``agent``."""
        listeners = self._agent_listeners.get(agent, [])
        if listener in listeners:
            listeners.remove(listener)

    def notify_agents(self, percept: Percept, *agents: str) -> None:
        """Push ``percept`` to the listeners of ``agents`` (all registered agents if none)."""
        for agent in agents:
            self._require_agent(agent, AgentException)
        for agent in agents or tuple(self._agents):
            for listener in list(self._agent_listeners.get(agent, ())):
                tell(listener, "handle_percept", agent, percept)

    def notify_agents_via_entity(self, percept: Percept, *entities: str) -> None:
        """Push ``percept`` to the agents associated with ``entities`` (each agent once)."""
        for entity in entities:
            self._require_entity(entity, EntityException)
        holders = {agent for entity in entities for agent in self._holders[entity]}
        targets = sorted(holders, key=self._rank.__getitem__)  # in registration order
        if targets:
            self.notify_agents(percept, *targets)

    # ---- perceiving and acting --------------------------------------------------------------

    def get_all_percepts(self, agent: str, *entities: str) -> dict[str, list[Percept]]:
        """The current percepts of ``agent``'s entities (all associated ones if none given)."""
        targets = self._targets(agent, entities, PerceiveException)
        if self._state not in (EnvironmentState.PAUSED, EnvironmentState.RUNNING):
            raise PerceiveException(
                f"environment '{self.name}' gives no percepts while {self._state.value}"
            )
        return {entity: list(self.percepts_for_entity(entity)) for entity in targets}

    def perform_action(
        self, agent: str, action: Action, *entities: str
    ) -> dict[str, Percept | None]:
        """Perform ``action`` through ``agent``'s entities (all associated ones if none given)."""
        try:
            targets = self._targets(agent, entities, ActException)
        except ActException as error:
            kind = (
                ActExceptionKind.NOT_REGISTERED
                if agent not in self._agents
                else ActExceptionKind.WRONG_ENTITY
            )
            raise ActException(str(error), kind) from None
        if not targets:
            raise ActException(
                f"agent '{agent}' has no entity in environment '{self.name}' to perform "
                f"{action}",
                ActExceptionKind.NO_ENTITIES,
            )
        if self._state is not EnvironmentState.RUNNING:
            raise ActException(
                f"environment '{self.name}' is {self._state.value}; {action} was not performed",
                ActExceptionKind.NOT_RUNNING,
            )
        return {entity: self.perform_entity_action(entity, action) for entity in targets}
