"""The kinds of things an agent reports: events its listeners see (the trace, the
inspector) and problems it warns about. Shared by the interpreter (``goalagent.kb``) and the
agent (``goalagent.agent``); plain enums, no behaviour."""

from __future__ import annotations

from enum import Enum


class _Named(str, Enum):
    """An enum whose members format as their value (``f"{kind:>12}"`` shows ``fired``)."""

    def __str__(self) -> str:
        return str(self.value)

    def __format__(self, spec: str) -> str:
        return format(str(self.value), spec)


class EventKind(_Named):
    """What happened, as told to an agent's listeners, in the order it happened."""

    PERCEPTS = "percepts"  # the percepts of a new cycle
    MESSAGE_RECEIVED = "received"
    RULE_TRIED = "rule"  # a rule's condition was evaluated: its instantiations
    RULE_FIRED = "fired"  # with its bindings and the actions it performed
    ACTION_REFUSED = "refused"  # an action of a rule was not enabled
    PRECONDITION_FAILED = "precondition"  # one actionspec's precondition did not hold
    BELIEF_ADDED = "inserted"
    BELIEF_DELETED = "deleted"
    GOAL_ADOPTED = "adopted"
    GOAL_DROPPED = "dropped"
    GOAL_ACHIEVED = "achieved"  # removed by blind commitment
    MODULE_ENTERED = "entered"
    MODULE_LEFT = "left"
    WARNING = "warning"  # a problem the agent warns about and goes on (its text)


class ProblemKind(_Named):
    """What went wrong (a warning: the agent goes on)."""

    CONDITION_ERROR = "condition"  # a Prolog error in a rule's condition
    PROLOG_WARNING = "warning"  # a warning SWI-Prolog gave while a rule ran
    ACTION_ERROR = "action"  # a Prolog error performing an action (insert, a postcondition)
    ACTION_NOT_CLOSED = "open"  # a user action with variables after its precondition
    PRECONDITION_ERROR = "precondition"  # a Prolog error in an actionspec's precondition
    ENVIRONMENT_REFUSED = "environment"  # the environment could not perform an action
    PERCEPTS_UNAVAILABLE = "percepts"  # the environment could not give percepts
    RECEIVER_UNBOUND = "receiver"  # a message whose receiver is a variable
    DELIVERY_FAILED = "delivery"  # a message that could not be delivered
    LIMIT_EXCEEDED = "limit"  # a rule passed an inference or time limit
    GOAL_UNCHECKED = "goal_check"  # checking a goal passed a limit or raised: it is kept
