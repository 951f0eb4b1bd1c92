"""``goalagent run --inspect``: the mind inspector, a web page showing every agent live.

Per agent: beliefs, goals, percepts, mailbox, the rules tried and fired in its last cycle
with their bindings, and the panels installed extensions add (the robot's afford/6 table
and reliability plot, its camera frame with perception boxes). Controls: pause, step one
cycle, run, breakpoints (``FILE:LINE`` or a condition), queries, and a history of past
cycles to scroll back through. The run starts paused; the page stays up after the agents
end, until Ctrl-C.

This module is the run thread's side, the :class:`~goalagent.debugger.FrontEnd` of a
:class:`~goalagent.debugger.Debugger`: it takes snapshots of agents (Prolog is only called
here, on the thread running the agents) and carries out the browsers' commands, which
``server.InspectorServer`` queues.
"""

from __future__ import annotations

import base64
import queue
import time
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from rich.console import Console

from goalagent.agent import Event, EventKind
from goalagent.agent.events import show_term
from goalagent.debugger import Debugger, DebuggerError, Stop
from goalagent.extensions import Extension, InspectorPanel, PanelView
from goalagent.inspector.environment_panel import EnvironmentPanel
from goalagent.inspector.server import Command, InspectorServer

if TYPE_CHECKING:
    from goalagent.agent import Agent

PUBLISH_EVERY = 0.25  # seconds between states pushed while the agents run freely
EVENTS_KEPT = 400  # events of one cycle shown at most
_SHOWN = {kind for kind in EventKind if kind is not EventKind.PERCEPTS}


def _event_json(event: Event) -> dict[str, Any]:
    return {"kind": event.kind.value, "text": event.text,
            "pos": str(event.pos) if event.pos is not None else "",
            "bindings": [{name: show_term(value) for name, value in b.items()}
                         for b in event.instantiations]}


def _panel_json(view: PanelView) -> dict[str, Any]:
    image = ("data:image/png;base64," + base64.b64encode(view.png).decode("ascii")
             if view.png else "")
    return {"title": view.title, "columns": list(view.columns),
            "rows": [list(row) for row in view.rows], "image": image, "caption": view.caption}


class Inspector:
    """The mind inspector of one run (a debugger front end)."""

    def __init__(self, host: str, port: int, extensions: Sequence[Extension],
                 console: Console) -> None:
        self.console = console
        self.server = InspectorServer(host, port)
        self.host = host
        self.port = port
        self.panels: list[InspectorPanel] = [EnvironmentPanel()] + [
            make() for extension in extensions for make in extension.inspector_panels]
        self._events: dict[str, list[dict[str, Any]]] = {}  # the cycle in progress, per agent
        self._last: dict[str, list[dict[str, Any]]] = {}  # the last cycle's, per agent
        self._stop: Stop | None = None
        self._ended = False
        self._published = 0.0
        self._debugger: Debugger | None = None

    def attach(self, debugger: Debugger) -> None:
        """Observe ``debugger``'s run and serve the page."""
        self._debugger = debugger
        debugger.sandboxed = True  # a page's queries inspect minds, never the machine
        debugger.on_event = self._event
        debugger.on_cycle = self._cycle_ended
        self.port = self.server.start()
        self.console.print(f"inspector: {self.url} (the run starts paused; Ctrl-C stops)",
                           markup=False)

    @property
    def url(self) -> str:
        """The page's address with the run's token (nothing else is served)."""
        host = f"[{self.host}]" if ":" in self.host else self.host
        return f"http://{host}:{self.port}/?token={self.server.token}"

    # ------------------------------------------------------------------ debugger front end
    def wait(self, debugger: Debugger, stop: Stop) -> None:
        """Show the stop and carry out commands until one goes on."""
        self._stop = stop
        self._publish(debugger)
        while True:
            command = self._next_command()
            if command is None:
                continue
            if self._carry_out(debugger, command):
                self._stop = None
                self._publish(debugger)
                return

    def ended(self, debugger: Debugger) -> None:
        """The agents ended: answer queries until Ctrl-C."""
        self._ended = True
        self._stop = None
        self._publish(debugger)
        self.console.print(f"inspector: the agents have ended; the page stays up at "
                           f"{self.url} until Ctrl-C", markup=False)
        try:
            while True:
                command = self._next_command()
                if command is not None:
                    self._carry_out(debugger, command)
        except KeyboardInterrupt:
            self.console.print("inspector: stopped", markup=False)
        finally:
            self.server.stop()

    def _next_command(self) -> Command | None:
        """The next browser command, or None after half a second without one. Never an
        endless wait: after an agent's shell/1, SWI-Prolog leaves SIGINT's handler
        restarting interrupted system calls, and Ctrl-C would not end a wait for a lock."""
        try:
            return self.server.commands.get(timeout=0.5)
        except queue.Empty:
            return None

    # ------------------------------------------------------------------ observing
    def _event(self, event: Event) -> None:
        if event.kind not in _SHOWN or (event.kind is EventKind.RULE_TRIED
                                        and not event.instantiations):
            return
        events = self._events.setdefault(event.agent, [])
        if len(events) < EVENTS_KEPT:
            events.append(_event_json(event))

    def _cycle_ended(self, agent: Agent) -> None:
        self._last[agent.name] = self._events.pop(agent.name, [])
        self.server.record(self._snapshot(agent, panels=False))
        debugger = self._debugger
        assert debugger is not None
        while True:  # commands that came while the agents ran (pause, queries, breakpoints)
            try:
                command = self.server.commands.get_nowait()
            except queue.Empty:
                break
            self._carry_out(debugger, command)
        if time.monotonic() - self._published > PUBLISH_EVERY and not debugger.stepping:
            self._publish(debugger)

    # ------------------------------------------------------------------ commands
    def _carry_out(self, debugger: Debugger, command: Command) -> bool:
        """Does what the browser asked; True when the run goes on (step, run)."""
        message = command.message
        op = message.get("op")
        try:
            if op in ("step", "run") and not self._ended:
                debugger.resume(step=op == "step")
                return self._stop is not None
            if op == "pause":
                debugger.resume(step=True)  # stops after the cycle running now
            elif op == "break":
                debugger.add_breakpoint(str(message.get("text", "")))
                self._publish(debugger)
            elif op == "unbreak":
                debugger.remove_breakpoint(str(message.get("text", "")))
                self._publish(debugger)
            elif op == "query":
                agent = debugger.agent(str(message.get("agent", "")))
                text = str(message.get("text", ""))
                self.server.reply(command, {"type": "answer", "agent": agent.name,
                                            "query": text,
                                            "answers": debugger.query(agent, text)})
        except DebuggerError as err:
            self.server.reply(command, {"type": "error", "text": str(err)})
        return False

    # ------------------------------------------------------------------ state
    def _publish(self, debugger: Debugger) -> None:
        self._published = time.monotonic()
        system = debugger.system
        agents = [] if system is None else [self._snapshot(agent, panels=True)
                                            for agent in system.agents]
        stop = self._stop
        self.server.publish({
            "paused": stop is not None, "ended": self._ended,
            "reason": stop.reason if stop is not None else ("the agents have ended"
                                                            if self._ended else "running"),
            "agent": stop.agent.name if stop is not None and stop.agent is not None else "",
            "breakpoints": [b.text for b in debugger.breakpoints], "agents": agents})

    def _snapshot(self, agent: Agent, panels: bool) -> dict[str, Any]:
        """An agent as the page shows it (its panels only for the live view)."""
        debugger = self._debugger
        assert debugger is not None
        inside = self._stop is not None and self._stop.inside and self._stop.agent is agent
        mailbox = [f"{show_term(a['S'])}: {show_term(a['M'])}"
                   for a in agent.query("bel", "received(S, M)")]
        snapshot: dict[str, Any] = {
            "name": agent.name, "cycle": agent.cycle,
            "status": self._status(agent),
            "beliefs": [show_term(b) for b in agent.beliefs()
                        if not (hasattr(b, "name") and b.name == "received")],
            "goals": [", ".join(show_term(fact) for fact in goal) for goal in agent.goals()],
            "percepts": [show_term(p) for p in agent.report.percepts],
            "mailbox": mailbox,
            "events": self._events.get(agent.name, []) if inside else self._last.get(
                agent.name, []),
            "events_of": "this cycle so far" if inside else "the last cycle",
        }
        if panels and debugger.context is not None:
            views = [panel.view(debugger.context, agent) for panel in self.panels]
            snapshot["panels"] = [_panel_json(view) for view in views if view is not None]
        return snapshot

    def _status(self, agent: Agent) -> str:
        """``failed``, ``terminated``, or nothing for a live agent (the page's status says
        whether the run is paused or running; the agent's card must not contradict it)."""
        system = self._debugger.system if self._debugger is not None else None
        if system is not None and agent.name in system.failures:
            return "failed"
        return "terminated" if agent.terminated else ""
