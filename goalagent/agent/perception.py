"""What an agent takes in at the start of a cycle: its percepts (from its environment
through ``AgentIO``, and its due GOAL 7 timers) and the messages its ``Postman`` holds,
put into its mental state and its cycle report and told to its listeners."""

from __future__ import annotations

from typing import TYPE_CHECKING

from goalagent.agent.actions import ActionFailed
from goalagent.agent.events import message_event, percepts_event
from goalagent.agent.problems import cause_traceback, warning_text
from goalagent.agent.timers import due_percepts
from goalagent.events import ProblemKind
from goalagent.kb.interpreter_requests import Problem
from goalagent.kb.terms import Term

if TYPE_CHECKING:
    from goalagent.agent.cycle import Agent


def perceive(agent: Agent) -> None:
    """The cycle's percepts and messages: the percept base replaced by this cycle's
    percepts (an environment that cannot give them is a warning, and none are given), the
    messages received."""
    percepts: list[Term] = []
    if agent.io is not None:
        try:
            percepts = agent.io.percepts()
        except ActionFailed as err:
            agent.warn(warning_text(Problem(ProblemKind.PERCEPTS_UNAVAILABLE, str(err)),
                                    agent.program))
            shown = cause_traceback(err)
            if shown is not None:
                agent.log(shown)
    if agent.timers:
        percepts = percepts + due_percepts(agent)
    agent.ms.set_percepts(percepts)
    agent.report.percepts = percepts
    if percepts and agent.listeners:
        agent.tell(percepts_event(agent.name, percepts))
    if agent.postman is not None:
        messages = agent.postman.collect(agent.name)
        agent.ms.receive(messages, replace=agent.program.messages_for_one_cycle)
        if agent.listeners:
            for sender, mood, content in messages:
                agent.tell(message_event(agent.name, sender, mood, content))
        agent.report.messages = messages
