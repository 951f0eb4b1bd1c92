"""Exceptions of the environment interface, after the Java EIS that GOAL uses.

Every exception carries a one-line message meant for a user (no traceback needed to act on it).
"""

from __future__ import annotations

from enum import Enum


class EnvironmentInterfaceException(Exception):
    """Base of everything the environment interface raises, so callers catch one type."""


class ManagementException(EnvironmentInterfaceException):
    """An invalid state transition, a bad init/reset parameter or a registration clash."""


class EntityException(EnvironmentInterfaceException):
    """An entity that does not exist, or one added twice."""


class RelationException(EnvironmentInterfaceException):
    """An agent-entity association that cannot be made or undone."""


class AgentException(EnvironmentInterfaceException):
    """An agent registered twice or not registered at all."""


class PerceiveException(EnvironmentInterfaceException):
    """Percepts that cannot be delivered (unknown agent, entity not associated, bad state)."""


class NoEnvironmentException(EnvironmentInterfaceException):
    """An environment name or ``package.module:Class`` path that names no environment."""


class TranslationException(EnvironmentInterfaceException, ValueError):
    """A Prolog term that has no interface-level form (e.g. an unbound variable)."""


class ActExceptionKind(Enum):
    """Why an action was not performed; agents report it as a warning and go on."""

    UNKNOWN_ACTION = "unknown action"
    WRONG_PARAMETERS = "wrong parameters"
    REFUSED = "refused"
    FAILURE = "failure"
    NOT_REGISTERED = "agent not registered"
    WRONG_ENTITY = "wrong entity"
    NO_ENTITIES = "no entities"
    NOT_RUNNING = "environment not running"


class ActException(EnvironmentInterfaceException):
    """An action that was not performed; ``kind`` says why."""

    def __init__(self, message: str, kind: ActExceptionKind = ActExceptionKind.FAILURE) -> None:
        super().__init__(message)
        self.kind = kind


class ActionRefused(ActException):
    """Raised by an action method that declines to act; the world must be left unchanged."""

    def __init__(self, message: str) -> None:
        super().__init__(message, ActExceptionKind.REFUSED)
