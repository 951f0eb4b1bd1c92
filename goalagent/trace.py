"""``goalagent run --trace[=KINDS] [--trace-file F]``: the agents' events as lines people read.

Every line names the agent and its cycle (``robot #3  fired ...``). KINDS (comma-separated)
choose what is shown, each exactly: percepts (as changes: ``+on(c,table) -on(c,a)``), rules,
actions (a firing's actions, one ``action`` line each unless rules are shown too: then the
rule's line carries them), beliefs, goals, messages, warnings, modules; ``all`` is every one.
Rules tried with no instantiation are left out unless ``idle`` is asked for. A trace file is
written as JSON lines when its name ends in ``.jsonl`` (one object per event, with the rule's
position and bindings), as text otherwise, atomically when the run ends. User data is never
read as Rich markup: lines are built as ``rich.text.Text``.
"""

from __future__ import annotations

import difflib
import json
from collections.abc import Iterable
from pathlib import Path

from rich.console import Console
from rich.text import Text

from goalagent.agent import Event, EventKind
from goalagent.agent.events import show_term
from goalagent.console import LastingConsole
from goalagent.kb.terms import Term
from ondisk import AtomicFile, check_target

KINDS: dict[str, frozenset[EventKind]] = {
    "percepts": frozenset({EventKind.PERCEPTS}),
    "rules": frozenset({EventKind.RULE_TRIED, EventKind.RULE_FIRED}),
    # A firing's actions: its line when rules are shown too, else one `action` line each.
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
ACTION = "action"  # the label of an action line (actions traced without their rules)


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


def _record(event: Event, label: str, text: str) -> dict:
    """The JSON object of one event (an action line: ``kind`` action)."""
    kind = "action" if label == ACTION else event.kind.name.lower()
    record: dict = {"agent": event.agent, "cycle": event.cycle, "kind": kind, "text": text}
    if event.module is not None:
        record["module"] = event.module
    if event.pos is not None:
        record["pos"] = str(event.pos)
    if event.instantiations:
        record["bindings"] = [{name: show(value) for name, value in bindings.items()}
                              for bindings in event.instantiations]
    return record


class TracePrinter:
    """A listener (``agent.listen``) writing the chosen events: to a Rich console (styled,
    never markup) or to a file (text, or JSON lines for ``.jsonl``)."""

    def __init__(self, kinds: Iterable[EventKind], idle: bool = False, *,
                 console: Console | None = None, file: Path | None = None) -> None:
        self.kinds = frozenset(kinds)
        self.idle = idle
        self.console = console if console is not None or file is not None else LastingConsole(
            highlight=False, soft_wrap=True, emoji=False)
        self.path = None if file is None else check_target(file)
        self._file: AtomicFile | None = None  # made at the first line (nothing to leave before)
        self._failure: OSError | None = None
        self._json = file is not None and file.suffix in (".jsonl", ".json")
        self._percepts: dict[str, set[str]] = {}

    def __call__(self, event: Event) -> None:
        if event.kind not in self.kinds:
            return
        if event.kind is EventKind.RULE_FIRED and EventKind.RULE_TRIED not in self.kinds:
            for action in event.actions:  # actions without rules: the actions alone
                self._show(event, ACTION, action)
            return
        text = self.text(event)
        if text is not None:
            self._show(event, str(event.kind), text)

    def _show(self, event: Event, label: str, text: str) -> None:
        """One line of ``event`` (``label``: its kind, or ``action``) where it goes."""
        if self.path is not None:
            line = (json.dumps(_record(event, label, text)) if self._json
                    else self.line(event, text, label))
            self._write(line + "\n")
        if self.console is not None:
            self.console.print(Text.assemble((event.agent, "dim"), " ",
                                             (f"#{event.cycle:<3}", "dim"), " ",
                                             (f"{label:>12}", "cyan"), " ", text))

    @staticmethod
    def line(event: Event, text: str, label: str | None = None) -> str:
        """One plain text line (``label``: what it shows, default the event's kind)."""
        return f"{event.agent} #{event.cycle:<3} {label or event.kind:>12} {text}"

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
        if event.kind is EventKind.RULE_TRIED and not event.instantiations and not self.idle:
            return None
        return event.text

    def _write(self, line: str) -> None:
        """Add a line to the trace file; after a write error (a full disk) the file is
        dropped and :meth:`close` reports it, the run goes on."""
        if self._failure is not None or self.path is None:
            return
        try:
            if self._file is None:
                self._file = AtomicFile(self.path)
            self._file.write(line)
        except OSError as error:
            self._failure = error
            if self._file is not None:
                self._file.discard()

    def close(self) -> None:
        """Put the trace file in place; ``OSError`` if it could not be written (the file
        that was there before is then left as it was)."""
        if self.path is None:
            return
        self._write("")  # a trace with no line is still a file
        path, self.path = self.path, None
        if self._failure is None and self._file is not None:
            try:
                self._file.commit()
            except OSError as error:
                self._failure = error
        if self._failure is not None:
            reason = self._failure.strerror or self._failure
            raise OSError(f"cannot write the trace file {path}: {reason}")
