"""The actions the interpreter leaves to Python: user actions sent to the environment (the
``AgentIO`` seam, so the agent knows nothing of EIS) and ``print``/``log`` output."""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

from goalagent.agent.problems import warning_text
from goalagent.console import printable
from goalagent.events import ProblemKind
from goalagent.kb.interpreter_requests import Firing, Problem
from goalagent.kb.terms import Atom, Struct, Term

if TYPE_CHECKING:
    from goalagent.agent.cycle import Agent


class ActionFailed(Exception):
    """Raised by an ``AgentIO`` (or a ``Postman``) when an action could not be performed."""


class AgentIO(Protocol):
    """What an agent needs from its environment (an EIS entity, or nothing)."""

    def percepts(self) -> list[Term]: ...

    def act(self, action: Struct | Atom) -> None: ...


def act_on_environment(agent: Agent, firing: Firing, index: int, action: Term) -> bool:
    """Sends a closed user action to the environment; False (with a warning) when it could
    not perform it. Either way the action counts as performed: the environment was asked."""
    assert agent.io is not None
    try:
        agent.io.act(action)  # type: ignore[arg-type]
    except ActionFailed as err:
        agent.warn(warning_text(Problem(ProblemKind.ENVIRONMENT_REFUSED, str(err), firing,
                                        index, term=action), agent.program))
        return False
    return True


def output(agent: Agent, text: str, log: bool) -> None:
    """``print/1`` writes a line on the agent's output; ``log/1`` goes where warnings go
    (printable there). A sandboxed agent's line is printable too: it may not drive the
    terminal (escape sequences set its title, its clipboard, what it shows)."""
    if log:
        agent.log(f"log: agent {agent.name}: {text}")
    else:
        print(printable(text) if agent.ms.limits.sandbox else text, file=agent.output,
              flush=True)
