"""GOAL 7's timer and channel actions, with GOAL's semantics (its ``RunState``):

- ``starttimer(Name, Interval, Duration)`` (milliseconds) starts a timer -- restarting one
  of that name -- that raises the percept ``timer(Name, Elapsed)`` every ``Interval`` for
  ``Duration``: the first after one interval, ``Elapsed`` the multiple of the interval that
  has passed, the last one's ``Elapsed`` equal to ``Duration``. Each firing is perceived
  once, in the agent's next cycle (several firings since its last cycle: one percept each).
- ``canceltimer(Name, ...)`` stops timers; one not running is a warning.
- ``subscribe(Channel, ...)`` / ``unsubscribe(Channel, ...)``: a message sent to a channel
  reaches every agent subscribed to it (``LocalPostman``).

Timers run on the wall clock, as GOAL's do (agents are not simulated in rounds).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

from goalagent.kb.terms import Struct, Term, Var, format_term

if TYPE_CHECKING:
    from goalagent.agent.cycle import Agent

MAX_TIMERS = 1000
"""Timers one agent may run at once (each is one dictionary entry)."""


@dataclass
class Timer:
    """A running timer: when it started, its interval and duration (seconds), and how many
    of its firings have been perceived."""

    name: Term
    start: float
    interval: float
    duration: float
    perceived: int = 0


def perform(agent: Agent, name: str, args: list[Term]) -> None:
    """Does one of GOAL 7's timer or channel actions for ``agent``."""
    if any(isinstance(arg, Var) for arg in args):
        agent.warn(f"{name}({', '.join(format_term(a) for a in args)}): an argument is not "
                   "bound; not done")
        return
    if name == "starttimer":
        _start(agent, *args)
    elif name == "canceltimer":
        for timer in args:
            if agent.timers.pop(format_term(timer), None) is None:
                agent.warn(f"timer '{format_term(timer)}' was not running or already "
                           "cancelled.")
    else:
        change = getattr(agent.postman, name, None)
        for channel in args:
            if change is not None:
                change(agent.name, format_term(channel))


def _start(agent: Agent, name: Term, interval: Term, duration: Term) -> None:
    if not (isinstance(interval, int) and isinstance(duration, int) and interval > 0
            and duration >= 0):
        agent.warn(f"starttimer({format_term(name)}, {format_term(interval)}, "
                   f"{format_term(duration)}): the interval and duration are milliseconds "
                   "(whole numbers, the interval above 0); not started")
        return
    key = format_term(name)
    if key not in agent.timers and len(agent.timers) >= MAX_TIMERS:
        agent.warn(f"starttimer({key}, ..): {MAX_TIMERS} timers are running; not started")
        return
    agent.timers[key] = Timer(name, time.monotonic(), interval / 1000, duration / 1000)


def due_percepts(agent: Agent) -> list[Term]:
    """The ``timer(Name, Elapsed)`` percepts of the firings since the agent's last cycle;
    finished timers are removed."""
    now = time.monotonic()
    percepts: list[Term] = []
    for key, timer in list(agent.timers.items()):
        interval_ms = round(timer.interval * 1000)
        duration_ms = round(timer.duration * 1000)
        last = max(1, -(-duration_ms // interval_ms))  # the firing that reaches Duration
        fired = min(int((now - timer.start) / timer.interval), last)
        for firing in range(timer.perceived + 1, fired + 1):
            percepts.append(Struct("timer", (timer.name,
                                             min(firing * interval_ms, duration_ms))))
        timer.perceived = max(timer.perceived, fired)
        if timer.perceived >= last:
            del agent.timers[key]
    return percepts
