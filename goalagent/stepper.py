"""``goalagent run --step``: stepping agents at a terminal prompt, for people without a browser.

After each cycle (and at breakpoints) the run stops and shows what the cycle did, then
reads commands on stdin; the prompt and everything it shows go to stderr, as stdout
belongs to the agents' ``print/1``. When stdin ends the run goes on to its end.
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING, TextIO

from rich.console import Console

from goalagent.agent.events import show_term
from goalagent.debugger import Debugger, DebuggerError, Stop

if TYPE_CHECKING:
    from goalagent.agent import Agent

HELP = """\
  n (or Enter)      run the next cycle and stop after it
  c                 continue until a breakpoint (or the end)
  b FILE:LINE       stop when the rule on that line applies (before it acts)
  b bel(...)        stop after the cycle in which the condition becomes true
                    (also goal(...), a-goal(...), goal-a(...), percept(...))
  b                 list the breakpoints;  d TEXT  delete one
  q bel(...)        ask the agent a query (q @NAME bel(...) asks agent NAME)
  m                 the agent's beliefs, goals and percepts
  ?                 this help"""


class TerminalStepper:
    """The ``FrontEnd`` of ``--step``: a prompt on the terminal."""

    def __init__(self, stdin: TextIO | None = None, console: Console | None = None) -> None:
        self.stdin = stdin or sys.stdin
        self.console = console or Console(stderr=True, highlight=False, soft_wrap=True, emoji=False)

    def say(self, text: str) -> None:
        self.console.print(text, markup=False)

    def wait(self, debugger: Debugger, stop: Stop) -> None:
        """Show where the run stopped, then read commands until one goes on."""
        agent = stop.agent
        title = f"{agent.name} #{agent.cycle}: " if agent is not None else ""
        self.say(f"-- {title}{stop.reason}")
        if agent is not None and not stop.inside and agent.last_report is not None:
            for fired in agent.last_report.fired:
                bindings = ", ".join(f"{k}={show_term(v)}" for k, v in fired.bindings.items())
                self.say(f"   fired {fired.shown} {fired.pos} [{bindings}] -> "
                         f"{' + '.join(fired.actions) or '(block)'}")
        while True:
            self.console.print("(goalagent) ", end="", markup=False)
            line = self.stdin.readline()
            if not line:  # end of input: no one to ask any more
                self.say("(end of input: running to the end)")
                debugger.breakpoints.clear()
                debugger.resume(step=False)
                return
            command, _, argument = line.strip().partition(" ")
            argument = argument.strip()
            if command in ("", "n"):
                debugger.resume(step=True)
                return
            if command == "c":
                debugger.resume(step=False)
                return
            try:
                self._command(debugger, stop, command, argument)
            except DebuggerError as err:
                self.say(f"error: {err}")

    def ended(self, debugger: Debugger) -> None:
        """Nothing to keep: the summaries follow."""

    def _command(self, debugger: Debugger, stop: Stop, command: str, argument: str) -> None:
        """A command that does not go on."""
        if command == "b" and argument:
            self.say(f"breakpoint {debugger.add_breakpoint(argument).text}")
        elif command == "b":
            self.say("\n".join(b.text for b in debugger.breakpoints) or "no breakpoints")
        elif command == "d":
            debugger.remove_breakpoint(argument)
            self.say(f"deleted {argument}")
        elif command == "q":
            agent, query = self._addressed(debugger, stop, argument)
            answers = debugger.query(agent, query)
            self.say("\n".join(answers) if answers else "no")
        elif command == "m":
            agent, _ = self._addressed(debugger, stop, argument)
            self._mental_state(agent)
        elif command == "?":
            self.say(HELP)
        else:
            self.say(f"unknown command {command!r}; ? lists the commands")

    @staticmethod
    def _addressed(debugger: Debugger, stop: Stop, argument: str) -> tuple[Agent, str]:
        """``@NAME rest`` names an agent; otherwise the stopped agent (or the first)."""
        if argument.startswith("@"):
            name, _, rest = argument[1:].partition(" ")
            return debugger.agent(name), rest.strip()
        if stop.agent is not None:
            return stop.agent, argument
        assert debugger.system is not None
        return debugger.system.agents[0], argument

    def _mental_state(self, agent: Agent) -> None:
        self.say(f"beliefs of {agent.name}:")
        for belief in agent.beliefs():
            self.say(f"   {show_term(belief)}")
        self.say("goals:")
        for goal in agent.goals():
            self.say("   " + ", ".join(show_term(fact) for fact in goal))
        if agent.report.percepts:  # the cycle in progress, or the last one
            self.say("percepts:")
            for percept in agent.report.percepts:
                self.say(f"   {show_term(percept)}")
