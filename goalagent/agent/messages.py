"""Messages between agents: the ``Postman`` seam (delivery between the agents of one
system), an in-process postman, and GOAL's ``send``/``sendonce`` actions."""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

from goalagent.agent.actions import ActionFailed
from goalagent.agent.problems import warning_text
from goalagent.events import ProblemKind
from goalagent.kb.interpreter_requests import Firing, Problem
from goalagent.kb.terms import Struct, Term, Var, format_term

if TYPE_CHECKING:
    from goalagent.agent.cycle import Agent


class Postman(Protocol):
    """Message delivery between the agents of one system."""

    def agents(self) -> list[str]: ...

    def deliver(self, sender: str, receivers: list[str], mood: str, content: Term) -> None: ...

    def collect(self, receiver: str) -> list[tuple[str, str, Term]]: ...


class LocalPostman:
    """A postman for one or more agents in this process: messages wait until collected."""

    def __init__(self) -> None:
        self._boxes: dict[str, list[tuple[str, str, Term]]] = {}
        self._channels: dict[str, set[str]] = {}  # GOAL 7's channels: their subscribers

    def register(self, name: str) -> None:
        """Gives ``name`` a mailbox."""
        self._boxes.setdefault(name, [])

    def agents(self) -> list[str]:
        return list(self._boxes)

    def subscribe(self, agent: str, channel: str) -> None:
        """GOAL 7's ``subscribe(Channel)``: messages sent to the channel reach ``agent``."""
        self._channels.setdefault(channel, set()).add(agent)

    def unsubscribe(self, agent: str, channel: str) -> None:
        self._channels.get(channel, set()).discard(agent)

    def deliver(self, sender: str, receivers: list[str], mood: str, content: Term) -> None:
        for receiver in receivers:
            if receiver not in self._boxes and self._channels.get(receiver):
                for member in sorted(self._channels[receiver]):
                    self._boxes[member].append((sender, mood, content))
                continue
            if receiver not in self._boxes:
                raise ActionFailed(f"no agent called {receiver!r} to send to")
            self._boxes[receiver].append((sender, mood, content))

    def collect(self, receiver: str) -> list[tuple[str, str, Term]]:
        messages, self._boxes[receiver] = self._boxes.get(receiver, []), []
        return messages


def _has_variables(term: Term) -> bool:
    if isinstance(term, Var):
        return True
    if isinstance(term, Struct):
        return any(_has_variables(arg) for arg in term.args)
    if isinstance(term, list):
        return any(_has_variables(item) for item in term)
    return False


def send(agent: Agent, firing: Firing, index: int, once: bool, mood: str, receiver: Term,
         content: Term) -> bool:
    """``Receiver.send(MoodContent)`` (``sendonce`` when ``once``): believes ``sent/2`` for
    every receiver and delivers the message; False when it is not enabled (a receiver not
    bound, nothing new for sendonce, delivery failed)."""
    action = firing.rule.rule.actions[index]
    if _has_variables(receiver):
        text = f"{format_term(receiver)}.{action.name}({mood}{format_term(content)})"
        agent.warn(warning_text(Problem(ProblemKind.RECEIVER_UNBOUND, text, firing, index),
                                agent.program))
        return False
    if receiver in ("all", "allother"):  # (only a broadcast lists every agent)
        everyone = agent.postman.agents() if agent.postman is not None else [agent.name]
        receivers = [name for name in everyone if receiver == "all" or name != agent.name]
    else:
        receivers = [str(receiver)]
    fresh = [name for name in receivers if agent.ms.add_sent(name, mood, content) or not once]
    if once and not fresh:
        return False
    if agent.postman is not None and fresh:
        try:
            agent.postman.deliver(agent.name, fresh, mood, content)
        except ActionFailed as err:
            agent.warn(warning_text(Problem(ProblemKind.DELIVERY_FAILED, str(err), firing,
                                            index), agent.program))
            return False
    return True
