"""An agent as others see it: queries on its mental state, its beliefs and goals, and what
it tells them -- events to its listeners, warnings and log lines.

``Agent`` (cycle.py) adds loading a program and running the reasoning cycle; this base holds
what a debugger, an inspector, a test or a system of agents reads and hears of it.
"""

from __future__ import annotations

import dataclasses
import sys
from collections.abc import Callable

from goalagent.agent.events import Event, Listener, Tracer, plain_variables, readable
from goalagent.agent.reports import CycleReport
from goalagent.events import EventKind
from goalagent.kb.mentalstate import MentalState
from goalagent.kb.terms import Term

Bindings = dict[str, Term]


class AgentView:
    """What others see of an agent named ``name``: its mental state (``ms``, made by the
    subclass), the listeners told its events and the warnings it gives (each to ``warn``,
    default: printed on stderr); ``tracer`` is called with (agent, kind, text) for every
    event."""

    ms: MentalState

    def __init__(self, name: str, *, tracer: Tracer | None = None,
                 warn: Callable[[str], None] | None = None) -> None:
        self.name = name
        self.listeners: list[Listener] = []
        if tracer is not None:
            self.listen(lambda event: tracer(event.agent, event.kind, event.text))
        self._warn = warn or (lambda message: print(message, file=sys.stderr))
        self._warned: dict[str, int] = {}  # each warning given: how often
        self.cycle = 0
        self.report = CycleReport(0)  # the cycle in progress (the last one between cycles)

    def query(self, op: str, text: str, *, confined: bool = False, sandboxed: bool = False,
              limit: int | None = None) -> list[Bindings]:
        """The answers of a mental-state query, as Python values.

        Args:
            op: ``bel``, ``goal``, ``a-goal``, ``goal-a`` or ``percept``.
            text: the query in Prolog (``count(X)``, ``on(X, Y), X \\= a``).
            confined: check it as the agent's own code is, in its sandbox if it has one (a
                query a user typed in the debugger); False: the query is trusted.
            sandboxed: check it so, and in the sandbox whether the agent has one or not
                (a query or condition a web page sent the mind inspector).
            limit: at most this many answers (the first ones); None: all of them.

        Returns:
            One mapping per answer, from each variable of ``text`` to its value (``Atom``
            for an atom, ``str`` for a string, ``Struct`` for a compound, numbers and lists
            as themselves); ``[]`` when there is none, ``[{}]`` for a yes without variables.

        Raises:
            KBError: the query is not valid Prolog or raised an error.
        """
        return self.ms.query(op, text, trusted=not (confined or sandboxed),
                             sandboxed=sandboxed, limit=limit)

    def beliefs(self) -> list[Term]:
        """The agent's beliefs (its belief base's facts), in order."""
        return self.ms.beliefs()

    def goals(self) -> list[list[Term]]:
        """The agent's goals, each as the list of its facts (``on(a,b), on(b,c)`` is one goal
        of two facts)."""
        return self.ms.goals()

    def close(self) -> None:
        """Free the agent's Prolog module."""
        self.ms.close()

    def listen(self, listener: Listener) -> None:
        """Tell ``listener`` every event from now on (the trace, an inspector)."""
        self.listeners.append(listener)

    def tell(self, event: Event) -> None:
        """Tell the listeners an event (stamped with the current cycle; fresh variables in its
        text shown as ``_``)."""
        event = dataclasses.replace(readable(event), cycle=self.cycle)
        for listener in self.listeners:
            listener(event)

    def warn(self, message: str) -> None:
        """A warning: kept in the cycle report, shown (``warning: agent NAME: ...``) and
        told to the listeners. A warning given before is shown again once, saying so, and
        then no more (a rule failing every cycle would otherwise fill the screen). Prolog's
        variable numbers are left out of it (``f(_)``), so a repeat reads the same."""
        message = plain_variables(message)
        self.report.warnings.append(message)
        seen = self._warned.get(message, 0)
        self._warned[message] = seen + 1
        if seen == 0:
            self._warn(f"warning: agent {self.name}: {message}")
        elif seen == 1:
            self._warn(f"warning: agent {self.name}: again in cycle {self.cycle} (not shown "
                       f"again): {message}")
        if self.listeners:
            self.tell(Event(EventKind.WARNING, self.name, message))

    def log(self, message: str) -> None:
        """A line where warnings go (``log/1``), not a warning."""
        self._warn(message)
