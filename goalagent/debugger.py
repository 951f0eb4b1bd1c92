"""Pausing a run: stepping cycle by cycle, breakpoints on rules and on conditions, queries.

The one rule interpreter is only observed: a :class:`Debugger` is a run hook (between
cycles) and a listener of every agent (inside a cycle: the interpreter tells each step
synchronously, so blocking in the listener holds the agent right there). When it stops it
hands a :class:`Stop` to its front end -- a terminal prompt (``--step``) or the web mind
inspector (``--inspect``) -- which returns once the user says to go on, answering queries
and changing breakpoints meanwhile. All Prolog calls happen on the thread that runs the
agents (the front end's ``wait`` is called there).

Breakpoints: ``FILE:LINE`` stops when the rule written on that line is tried and applies
(before it acts); ``bel(...)``, ``goal(...)``, ``a-goal(...)``, ``goal-a(...)`` or
``percept(...)`` stops after the cycle in which it becomes true for an agent.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Protocol

from goalagent import ast
from goalagent.agent import Event, EventKind
from goalagent.agent.events import show_term
from goalagent.extensions import RunContext, RunHook
from goalagent.kb.engine import KBError
from goalagent.kb.terms import Term

if TYPE_CHECKING:
    from goalagent.agent import Agent
    from goalagent.mas import MultiAgentSystem

_QUERY = re.compile(r"\s*(bel|goal|a-goal|goal-a|percept)\s*\((.*)\)\s*\Z", re.DOTALL)
_RULE = re.compile(r"\s*(.+):(\d+)\s*\Z")
MAX_BREAKPOINTS = 100  # each condition breakpoint is a query per agent and cycle
MAX_ANSWERS = 100  # answers of a query shown at most (the rest is counted as "more")
MAX_ANSWER_CHARS = 10_000  # characters of one answer shown at most


class DebuggerError(ValueError):
    """A breakpoint or query the user wrote that cannot be used (the message says why)."""


def split_query(text: str) -> tuple[str, str]:
    """``bel(on(X, Y))`` as ``("bel", "on(X, Y)")``."""
    match = _QUERY.match(text)
    if match is None:
        raise DebuggerError(f"{text.strip()!r}: write a query as bel(...), goal(...), "
                            "a-goal(...), goal-a(...) or percept(...)")
    return match.group(1), match.group(2)


def answer_text(answers: list[dict[str, Term]]) -> list[str]:
    """Query answers as lines (``X=a, Y=b``; ``true`` for an answer without variables),
    each cut at ``MAX_ANSWER_CHARS``."""
    lines = [", ".join(f"{name}={show_term(value)}" for name, value in answer.items())
             or "true" for answer in answers]
    return [line if len(line) <= MAX_ANSWER_CHARS else
            f"{line[:MAX_ANSWER_CHARS]} ... ({len(line):,} characters)" for line in lines]


@dataclass(frozen=True)
class Breakpoint:
    """A rule (``file``, ``line``) or a condition (``op``, ``query``) to stop at."""

    text: str
    file: str = ""
    line: int = 0
    op: str = ""
    query: str = ""

    @classmethod
    def parse(cls, text: str) -> Breakpoint:
        """``agents/x.goal:12`` or ``bel(done(X))``."""
        text = text.strip()
        if _QUERY.match(text):
            op, query = split_query(text)
            return cls(text, op=op, query=query)
        match = _RULE.match(text)
        if match is None:
            raise DebuggerError(f"{text!r}: a breakpoint is FILE:LINE (a rule) or a "
                                "condition such as bel(done(X))")
        return cls(text, file=match.group(1), line=int(match.group(2)))

    def at(self, pos: ast.Pos | None) -> bool:
        """A rule written at ``pos`` is on this breakpoint's line of its file (the file as
        written, resolved, or as the end of the rule's path: ``x.goal``, ``agents/x.goal``)."""
        if not self.line or pos is None or pos.line != self.line:
            return False
        written, actual = self.file, str(pos.file)
        return (written == actual or actual.endswith("/" + written)
                or Path(written).resolve() == Path(actual).resolve())


@dataclass(frozen=True)
class Stop:
    """Where the run stands still: ``agent`` (None before the first cycle or after the
    last), ``reason`` in words, ``inside`` when held inside a cycle (at a rule)."""

    agent: Agent | None
    reason: str
    inside: bool = False
    event: Event | None = None


class FrontEnd(Protocol):
    """Where a stopped run waits (``wait`` returns when the user says step or continue) and
    what it does when the agents have ended (``ended``: the inspector stays up)."""

    def wait(self, debugger: Debugger, stop: Stop) -> None: ...

    def ended(self, debugger: Debugger) -> None: ...


@dataclass
class Debugger(RunHook):
    """Stepping and breakpoints over a run (a run hook and every agent's listener)."""

    front: FrontEnd
    stepping: bool = True  # stop after the next cycle (and before the first)
    breakpoints: list[Breakpoint] = field(default_factory=list)
    on_event: Callable[[Event], None] | None = None  # also told every event (the inspector)
    on_cycle: Callable[[Agent], None] | None = None  # also told after every cycle
    # queries and conditions always in the sandbox (the inspector's: a web page wrote them)
    sandboxed: bool = False
    system: MultiAgentSystem | None = None
    context: RunContext | None = None
    _truth: dict[tuple[str, str], bool] = field(default_factory=dict)
    _held_rules: set[tuple[str, int, str]] = field(default_factory=set)

    # ------------------------------------------------------------------ run hook
    def start(self, run: RunContext) -> None:
        """Listen to every agent (and those launched later); stop before the first cycle."""
        self.system, self.context = run.system, run
        run.system.listeners.append(self._event)
        for agent in run.system.agents:
            agent.listen(self._event)
        for breakpoint in self.breakpoints:
            self._note_truth(breakpoint)
        if self.stepping:
            self.front.wait(self, Stop(None, "before the first cycle"))

    def after_cycle(self, run: RunContext, agent: Agent) -> None:
        """Stop when stepping or when a condition breakpoint became true for ``agent``."""
        self._held_rules = {key for key in self._held_rules if key[2] != agent.name}
        if self.on_cycle is not None:
            self.on_cycle(agent)
        reason = self._condition_hit(agent)
        if reason is not None:
            self.front.wait(self, Stop(agent, reason))
        elif self.stepping:
            self.front.wait(self, Stop(agent, f"after cycle {agent.cycle}"))

    def finish(self, run: RunContext) -> None:
        """The agents ended (not when the run was interrupted): tell the front end."""
        if not getattr(run.system, "interrupted", False):
            self.front.ended(self)

    # ------------------------------------------------------------------ commands
    def resume(self, step: bool) -> None:
        """Go on: to the end of the next cycle (``step``) or until a breakpoint."""
        self.stepping = step

    def add_breakpoint(self, text: str) -> Breakpoint:
        """A new breakpoint from what the user wrote (``DebuggerError`` when unusable)."""
        breakpoint = Breakpoint.parse(text)
        if len(self.breakpoints) >= MAX_BREAKPOINTS and breakpoint not in self.breakpoints:
            raise DebuggerError(f"{breakpoint.text}: there are {MAX_BREAKPOINTS} breakpoints "
                                "already; remove one first")
        if breakpoint.op:
            self._check_query(breakpoint.op, breakpoint.query)
        elif self.system is not None and not self._rule_exists(breakpoint):
            raise DebuggerError(f"{breakpoint.text}: no rule starts on that line")
        if breakpoint not in self.breakpoints:
            self.breakpoints.append(breakpoint)
            self._note_truth(breakpoint)
        return breakpoint

    def remove_breakpoint(self, text: str) -> None:
        self.breakpoints = [b for b in self.breakpoints if b.text != text.strip()]

    def query(self, agent: Agent, text: str) -> list[str]:
        """The first ``MAX_ANSWERS`` answers of a query on ``agent`` as lines, confined as
        the agent's own code (``DebuggerError`` when malformed or refused)."""
        op, query = split_query(text)
        try:
            answers = agent.query(op, query, confined=True, sandboxed=self.sandboxed,
                                  limit=MAX_ANSWERS + 1)
        except KBError as err:
            raise DebuggerError(str(err)) from None
        more = ["... (more answers)"] if len(answers) > MAX_ANSWERS else []
        return answer_text(answers[:MAX_ANSWERS]) + more

    def agent(self, name: str) -> Agent:
        """The agent called ``name``."""
        assert self.system is not None
        for agent in self.system.agents:
            if agent.name == name:
                return agent
        raise DebuggerError(f"no agent called {name!r}")

    # ------------------------------------------------------------------ inside a cycle
    def _event(self, event: Event) -> None:
        if self.on_event is not None:
            self.on_event(event)
        if event.kind is not EventKind.RULE_TRIED or not event.instantiations:
            return
        for breakpoint in self.breakpoints:
            if breakpoint.at(event.pos):
                key = (breakpoint.file, breakpoint.line, event.agent)
                if key in self._held_rules:  # once per rule and cycle (forall, nesting)
                    return
                self._held_rules.add(key)
                agent = self.agent(event.agent)
                self.front.wait(self, Stop(agent, f"breakpoint {breakpoint.text}: "
                                           f"{event.text}", inside=True, event=event))
                return

    # ------------------------------------------------------------------ helpers
    def _condition_hit(self, agent: Agent) -> str | None:
        hit = None
        for breakpoint in self.breakpoints:
            if not breakpoint.op:
                continue
            key = (breakpoint.text, agent.name)
            was = self._truth.get(key, False)
            now = self._holds(agent, breakpoint)
            self._truth[key] = now
            if now and not was and hit is None:
                hit = f"breakpoint {breakpoint.text} became true"
        return hit

    def _note_truth(self, breakpoint: Breakpoint) -> None:
        """Whether a condition holds now for each agent (it stops when it *becomes* true)."""
        if breakpoint.op and self.system is not None:
            for agent in self.system.agents:
                self._truth[(breakpoint.text, agent.name)] = self._holds(agent, breakpoint)

    def _holds(self, agent: Agent, breakpoint: Breakpoint) -> bool:
        try:
            return bool(agent.query(breakpoint.op, breakpoint.query, confined=True,
                                    sandboxed=self.sandboxed, limit=1))
        except KBError:
            return False

    def _check_query(self, op: str, query: str) -> None:
        if self.system is not None and self.system.agents:
            try:
                self.system.agents[0].query(op, query, confined=True,
                                            sandboxed=self.sandboxed, limit=1)
            except KBError as err:
                raise DebuggerError(str(err)) from None

    def _rule_exists(self, breakpoint: Breakpoint) -> bool:
        assert self.system is not None
        return any(breakpoint.at(rule.pos) for agent in self.system.agents
                   for module in agent.program.modules for rule in ast.iter_rules(module.rules))
