"""``goalagent run --trace[=KINDS] [--trace-file F]``: the agents' events as lines people read.

Every line names the agent and its cycle (``robot #3  fired ...``). KINDS (comma-separated)
choose what is shown: percepts (as changes: ``+on(c,table) -on(c,a)``), rules, actions,
beliefs, goals, messages, warnings, modules; ``all`` is every one of them. Rules tried with
no instantiation are left out unless ``idle`` is asked for. A trace file is written as JSON
lines when its name ends in ``.jsonl`` (one object per event, with the rule's position and
bindings), as text otherwise, atomically when the run ends. User data is never read as Rich
markup: lines are built as ``rich.text.Text``.
"""

from __future__ import annotations

import difflib
import json
import os
import tempfile
from collections.abc import Iterable
from pathlib import Path
from typing import IO

from rich.console import Console
from rich.text import Text

from goalagent.agent import Event, EventKind
from goalagent.agent.events import show_term
from goalagent.kb.terms import Term

KINDS: dict[str, frozenset[EventKind]] = {
    "percepts": frozenset({EventKind.PERCEPTS}),
    "rules": frozenset({EventKind.RULE_TRIED, EventKind.RULE_FIRED}),
    "actions": frozenset({EventKind.RULE_FIRED, EventKind.ACTION_REFUSED,
                          EventKind.PRECONDITION_FAILED}),
    "beliefs": frozenset({EventKind.BELIEF_ADDED, EventKind.BELIEF_DELETED}),
    "goals": frozenset({EventKind.GOAL_ADOPTED, EventKind.GOAL_DROPPED,
                        EventKind.GOAL_ACHIEVED}),
    "messages": frozenset({EventKind.MESSAGE_RECEIVED}),
    "warnings": frozenset({EventKind.WARNING}),
    "modules": frozenset({EventKind.MODULE_ENTERED, EventKind.MODULE_LEFT}),
}
IDLE = "idle"  # also show rules tried with no instantiation


class TraceKindError(ValueError):
    """An unknown kind in ``--trace=KINDS`` (the message suggests the closest)."""


def parse_kinds(text: str) -> tuple[frozenset[EventKind], bool]:
    """The event kinds named by ``text`` (``all`` or comma-separated names) and whether idle
    rules are shown."""
    chosen: set[EventKind] = set()
    idle = False
    names = [name.strip().lower() for name in text.split(",") if name.strip()] or ["all"]
    for name in names:
        if name == "all":
            chosen.update(*KINDS.values())
        elif name == IDLE:
            idle = True
            chosen.update(KINDS["rules"])
        elif name in KINDS:
            chosen.update(KINDS[name])
        else:
            known = [*KINDS, "all", IDLE]
            close = difflib.get_close_matches(name, known, n=1)
            hint = f" (did you mean {close[0]}?)" if close else ""
            raise TraceKindError(f"--trace: unknown kind {name!r}{hint}; known: "
                                 f"{', '.join(known)}")
    return frozenset(chosen), idle


def show(term: Term) -> str:
    """A term as trace text: Prolog syntax, fresh variables as ``_``."""
    return show_term(term)


def _record(event: Event, text: str) -> dict:
    """The JSON object of one event."""
    record: dict = {"agent": event.agent, "cycle": event.cycle, "kind": event.kind.name.lower(),
                    "text": text}
    if event.module is not None:
        record["module"] = event.module
    if event.pos is not None:
        record["pos"] = str(event.pos)
    if event.bindings:
        record["bindings"] = [{name: show(value) for name, value in bindings.items()}
                              for bindings in event.bindings]
    return record


class _AtomicFile:
    """A text file written in the same folder under a temporary name (made at the first
    write), put in place by :meth:`close` (os.replace), so readers never see half a trace."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self._temporary = ""
        self._stream: IO[str] | None = None

    def write(self, line: str) -> None:
        if self._stream is None:
            handle, self._temporary = tempfile.mkstemp(
                dir=self.path.parent, prefix=f".{self.path.name}.", suffix=".tmp")
            self._stream = os.fdopen(handle, "w", encoding="utf-8")
        self._stream.write(line)

    def close(self) -> None:
        if self._stream is None:
            self.write("")
        assert self._stream is not None
        self._stream.close()
        os.chmod(self._temporary, 0o666 & ~_umask())
        os.replace(self._temporary, self.path)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


class TracePrinter:
    """A listener (``agent.listen``) writing the chosen events: to a Rich console (styled,
    never markup) or to a file (text, or JSON lines for ``.jsonl``)."""

    def __init__(self, kinds: Iterable[EventKind], idle: bool = False, *,
                 console: Console | None = None, file: Path | None = None) -> None:
        self.kinds = frozenset(kinds)
        self.idle = idle
        self.console = console if console is not None or file is not None else Console(
            highlight=False, soft_wrap=True, emoji=False)
        self._file = _AtomicFile(file) if file is not None else None
        self._json = file is not None and file.suffix in (".jsonl", ".json")
        self._percepts: dict[str, set[str]] = {}

    def __call__(self, event: Event) -> None:
        if event.kind not in self.kinds:
            return
        text = self.text(event)
        if text is None:
            return
        if self._file is not None:
            line = json.dumps(_record(event, text)) if self._json else self.line(event, text)
            self._file.write(line + "\n")
        if self.console is not None:
            self.console.print(Text.assemble((event.agent, "dim"), " ",
                                             (f"#{event.cycle:<3}", "dim"), " ",
                                             (f"{event.kind:>12}", "cyan"), " ", text))

    @staticmethod
    def line(event: Event, text: str) -> str:
        """One plain text line."""
        return f"{event.agent} #{event.cycle:<3} {event.kind:>12} {text}"

    def text(self, event: Event) -> str | None:
        """What to show for ``event``; None to leave it out (an idle rule, unchanged
        percepts)."""
        if event.kind is EventKind.PERCEPTS:
            now = {show(p) for p in event.term or []}  # type: ignore[union-attr]
            before = self._percepts.get(event.agent, set())
            self._percepts[event.agent] = now
            changes = [f"+{p}" for p in sorted(now - before)]
            changes += [f"-{p}" for p in sorted(before - now)]
            return " ".join(changes) or None
        if event.kind is EventKind.RULE_TRIED and not event.bindings and not self.idle:
            return None
        return event.text

    def close(self) -> None:
        """Put the trace file in place."""
        if self._file is not None:
            self._file.close()
            self._file = None

