"""The actions the interpreter leaves to Python: user actions sent to the environment (the
``AgentIO`` seam, so the agent knows nothing of EIS) and ``print``/``log`` output."""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

from goalagent.agent.errors import AgentError
from goalagent.agent.problems import cause_traceback, warning_text
from goalagent.console import printable
from goalagent.events import ProblemKind
from goalagent.kb.interpreter_requests import Firing, Problem
from goalagent.kb.terms import Atom, Struct, Term

if TYPE_CHECKING:
    from goalagent.agent.cycle import Agent


class ActionFailed(Exception):
    """Raised by an ``AgentIO`` (or a ``Postman``) when an action could not be performed;
    ``fatal``: the environment cannot take it at all (an unknown action, wrong parameters, no
    entity to do it), which stops the agent as GOAL's runtime does."""

    def __init__(self, message: str, *, fatal: bool = False) -> None:
        super().__init__(message)
        self.fatal = fatal


class AgentIO(Protocol):
    """What an agent needs from its environment (an EIS entity, or nothing)."""

    def percepts(self) -> list[Term]: ...

    def act(self, action: Struct | Atom) -> None: ...


def act_on_environment(agent: Agent, firing: Firing, index: int, action: Term) -> bool:
    """Sends a closed user action to the environment; False (with a warning) when it refused
    or failed to perform it. Either way the action counts as performed, as in GOAL: the
    environment was asked, its postcondition follows and the rule's next actions run. An
    action the environment cannot take at all (``ActionFailed.fatal``) stops the agent
    (``AgentError``), as GOAL's runtime stops it."""
    assert agent.io is not None
    try:
        agent.io.act(action)  # type: ignore[arg-type]
    except ActionFailed as err:
        text = warning_text(Problem(ProblemKind.ENVIRONMENT_REFUSED, str(err), firing, index,
                                    term=action), agent.program)
        shown = cause_traceback(err)
        if err.fatal:
            if shown is not None:
                agent.log(shown)
            raise AgentError(f"{text} (the agent is stopped, as GOAL stops an agent whose "
                             "action its environment cannot take)") from None
        agent.warn(text)
        if shown is not None:
            agent.log(shown)
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
