"""One GOAL agent: its reasoning cycle and everything around the one rule interpreter.

- ``cycle``: ``Agent`` -- loading a program, the modules of a cycle, exit options.
- ``view``: ``AgentView``, the base of ``Agent`` -- what others see of an agent: queries,
  beliefs and goals, its listeners, warnings and log lines.
- ``perception``: a cycle's percepts and messages; ``idleness``: the idle-agent warning.
- ``rules``: rule application -- modules run on the interpreter (``goalagent.kb``), whose
  requests it answers.
- ``actions``: environment actions (the ``AgentIO`` seam) and print/log.
- ``messages``: ``send``/``sendonce`` and the ``Postman`` seam.
- ``modules``: module calls, goal focus, the module an agent stays in.
- ``reports``: what a cycle did (``CycleReport``, ``FiredRule``, ``RunResult``).
- ``events``: what listeners see (``Event``, ``Tracer``); ``problems``: warning texts.
- ``checks``: ``validate_program``, the checks made when a program is loaded.
"""

from goalagent.agent.actions import ActionFailed, AgentIO
from goalagent.agent.checks import validate_program
from goalagent.agent.cycle import Agent, AgentError
from goalagent.agent.events import Event, Listener, Tracer
from goalagent.agent.messages import LocalPostman, Postman
from goalagent.agent.reports import CycleReport, FiredRule, RunResult
from goalagent.events import EventKind, ProblemKind

__all__ = [
    "ActionFailed",
    "Agent",
    "AgentError",
    "AgentIO",
    "CycleReport",
    "Event",
    "EventKind",
    "FiredRule",
    "Listener",
    "LocalPostman",
    "Postman",
    "ProblemKind",
    "RunResult",
    "Tracer",
    "validate_program",
]
