"""Noticing an agent that does nothing: cycles in a row without an action, a new percept or
a message, and the one warning when there have been enough of them while goals are left
(an agent that would otherwise run on without a word)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from goalagent.kb.terms import format_term

if TYPE_CHECKING:
    from goalagent.agent.cycle import Agent

IDLE_WARNING_CYCLES = 100
"""An agent with goals left that has done nothing for this many cycles is warned about once."""


def note_idleness(agent: Agent) -> None:
    """Counts the cycle just run as idle or not; warns once when ``agent.idle_warning``
    idle cycles in a row have passed and goals are left."""
    report, last = agent.report, agent.last_report
    if (report.acted or report.messages or agent.terminated or last is None
            or report.percepts != last.percepts):
        agent.idle_cycles = 0
        return
    agent.idle_cycles += 1
    if agent.idle_cycles == agent.idle_warning:
        goals = agent.goals()
        if goals:
            first = ", ".join(format_term(fact) for fact in goals[0])
            agent.warn(f"has done nothing for {agent.idle_cycles} cycles (no action, no new "
                       f"percept or message) and has {len(goals)} goal(s) left, e.g. "
                       f"{first}: no rule applies to them; it runs on until --max-cycles "
                       "or Ctrl-C")
