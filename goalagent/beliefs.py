"""Beliefs kept between runs: Prolog fact files loaded into agents and saved from them.

``goalagent run --load-beliefs FILE`` adds a file's facts to every agent's beliefs before it
starts; ``--save-beliefs FILE`` writes the final beliefs of the saved predicates (those the
installed extensions declare, e.g. the robot application's ``afford/6``, and those named with
``--save-predicate NAME/ARITY``), every ``--save-every`` while the run goes and before any
report at its end. Files are written atomically (``ondisk.write_atomically``), so kill -9 at
any moment leaves the last complete save. Files read are checked first: only ground facts,
nothing run, the checks of the extensions' saved predicates (e.g. afford/6's types).
"""

from __future__ import annotations

import re
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from goalagent.extensions import RunContext, RunHook, SavedPredicate, saved_predicates
from goalagent.kb.errors import KBError
from goalagent.kb.facts import FactCheck, FactFile, FactFileError, read_facts
from goalagent.kb.terms import Atom, Struct, Term, format_term, quote_atom
from goalagent.parser import GoalSyntaxError
from goalagent.parser.source import MAX_FACT_FILE_BYTES, Source, read_program_file
from ondisk import write_atomically

_BRACKETS = re.compile(r"[()\[\]{}]")
_EXACT_SCAN_DEPTH = 5000  # nesting from which the brackets are located exactly first

if TYPE_CHECKING:
    from goalagent.agent import Agent


def _check_nesting(text: str, file: str) -> None:
    """Brackets nested more than 200 deep (when they may pass 5,000) are an error at the
    first bracket too deep, before SWI reads the file: its reader recurses in C per level
    and would stop on a 100,000-deep list with a C-stack error located at the file's start.
    The count over every bracket is a quick bound; only a text that may pass it is scanned
    exactly (quotes, comments)."""
    depth = deepest = 0
    for match in _BRACKETS.finditer(text):
        depth = depth + 1 if match.group() in "([{" else max(depth - 1, 0)
        deepest = max(deepest, depth)
    if deepest > _EXACT_SCAN_DEPTH:  # else SWI's own check says more (guard.pl, 200 levels)
        Source(text, file)  # raises GoalSyntaxError at the first bracket too deep


def read_belief_file(path: str | Path,
                     predicates: Sequence[SavedPredicate] | None = None) -> FactFile:
    """The checked facts of a ``--load-beliefs`` file, kept in Prolog (close it, or use it
    in a ``with`` block). Only a regular file of at most ``MAX_FACT_FILE_BYTES`` is read;
    every clause must be a ground fact (a directive is refused, never run) and facts of
    ``predicates`` (default: those the installed extensions save, e.g. afford/6) must pass
    their checks. Raises ``GoalSyntaxError`` at the first bad clause's file:line:col."""
    if predicates is None:
        predicates = saved_predicates()
    text = read_program_file(path, MAX_FACT_FILE_BYTES)
    _check_nesting(text, str(path))
    checks = [FactCheck(predicate.template, condition, meaning) for predicate in predicates
              if predicate.template for condition, meaning in predicate.checks]
    try:
        return read_facts(text, str(path), checks)
    except FactFileError as error:
        raise GoalSyntaxError.at(error.pos, error.reason) from None


def load_beliefs(agents: Agent | Iterable[Agent], path: str | Path,
                 predicates: Sequence[SavedPredicate] | None = None) -> int:
    """Add the facts of a Prolog file to the agents' beliefs (before their first cycle),
    reading and checking the file once (see :func:`read_belief_file`); returns how many
    clauses it holds. A fact an agent cannot take (e.g. of one of its knowledge
    predicates) raises ``GoalSyntaxError`` at its position."""
    group = [agents] if not isinstance(agents, Iterable) else list(agents)
    with read_belief_file(path, predicates) as facts:
        for agent in group:
            try:
                agent.ms.add_facts(facts)
            except FactFileError as error:
                raise GoalSyntaxError.at(error.pos, f"agent {agent.name}: {error.reason}"
                                         ) from None
        return facts.count


def knows(agent: Agent, predicate: SavedPredicate) -> bool:
    """Whether ``predicate`` is one of the agent's (declared, believed or known)."""
    return bool(agent.query("bel", f"current_predicate({quote_atom(predicate.name)}/"
                                   f"{predicate.arity})"))


def _may_know(agent: Agent, predicate: SavedPredicate) -> bool:
    """:func:`knows`, or True when the agent cannot be asked (the save then says why)."""
    try:
        return knows(agent, predicate)
    except KBError:
        return True


def beliefs_of(agent: Agent, predicate: SavedPredicate) -> list[Term]:
    """The agent's current beliefs of ``predicate`` as terms, in belief-base order. Facts
    taking more memory than the agent's --max-memory (an agent stopped for holding too
    much) are not read: a KBError says so (writing them would take minutes)."""
    if not knows(agent, predicate):
        return []
    names = [f"A{index}" for index in range(predicate.arity)]
    text = f"{quote_atom(predicate.name)}({', '.join(names)})" if names else quote_atom(
        predicate.name)
    size = agent.query("bel", f"predicate_property({text}, size(Size))")
    most = agent.ms.limits.max_memory_bytes
    if size and isinstance(size[0]["Size"], int) and size[0]["Size"] > most:
        raise KBError(f"its facts take {size[0]['Size'] >> 20:,} MB, more than its "
                      f"--max-memory of {most >> 20:,} MB")
    if predicate.arity == 0:
        return [Atom(predicate.name) for _ in agent.query("bel", quote_atom(predicate.name))]
    facts: list[Term] = []
    for answer in agent.query("bel", text):
        args = tuple(answer[name] for name in names)
        if predicate.canonical is not None:
            args = predicate.canonical(args)
        facts.append(Struct(predicate.name, args))
    return facts


@dataclass(frozen=True)
class Saved:
    """What a save wrote: ``count`` facts, and the agents some of whose facts it could not
    write (name -> why; the file says so in a comment where those facts would be)."""

    count: int
    unsaved: dict[str, str]


def save_beliefs(agents: Iterable[Agent], predicates: Sequence[SavedPredicate],
                 path: Path) -> Saved:
    """Write every agent's beliefs of ``predicates`` as Prolog facts. The facts of a
    predicate an agent holds that cannot be read or written (one nested too deeply for
    Python, a cyclic one, too many for its limits) are left out with the reason: one bad
    agent never costs the others' save."""
    lines = [f"% {predicate.heading} saved by goalagent" for predicate in predicates]
    count = 0
    unsaved: dict[str, str] = {}
    for agent in agents:
        lines.append(f"% agent {agent.name}")
        for predicate in predicates:
            try:
                text = [format_term(fact) + "." for fact in beliefs_of(agent, predicate)]
            except (KBError, RecursionError) as error:
                reason = (f"{predicate.indicator}: "
                          + ("a fact nested too deeply to write"
                             if isinstance(error, RecursionError) else _one_line(str(error))))
                unsaved[agent.name] = "; ".join(filter(None, [unsaved.get(agent.name), reason]))
                lines.append(f"% not saved: {reason}")
                continue
            lines.extend(text)
            count += len(text)
    write_atomically(path, "\n".join(lines) + "\n")
    return Saved(count, unsaved)


def _one_line(text: str) -> str:
    """``text`` on one line, short enough for a comment in a saved file."""
    line = " ".join(text.split())
    return line if len(line) <= 200 else line[:200] + "..."


@dataclass(frozen=True)
class SaveInterval:
    """How often ``--save-every`` saves during a run: every ``cycles`` agent cycles, or every
    ``seconds`` of wall-clock time (checked after each cycle); neither: only at the end."""

    cycles: int | None = None
    seconds: float | None = None

    @classmethod
    def parse(cls, text: str) -> SaveInterval:
        """``100`` (cycles), ``30s``, ``5m`` or ``1h``; ``end`` saves only when the run ends.
        Raises ValueError with a readable message."""
        spec = text.strip().lower()
        if spec == "end":
            return cls()
        unit = {"s": 1, "m": 60, "h": 3600}.get(spec[-1:]) if spec else None
        number = spec[:-1] if unit else spec
        try:
            value = float(number) if unit else int(number)
        except ValueError:
            value = -1
        if not (0 < value <= 10**9):
            raise ValueError(f"--save-every {text!r}: expected a number of cycles (100), of "
                             "seconds (30s), minutes (5m) or hours (1h), or 'end'")
        return cls(seconds=value * unit) if unit else cls(cycles=int(value))


class BeliefSaver(RunHook):
    """The ``--save-beliefs`` hook: saves the saved predicates while the run goes (see
    :class:`SaveInterval`) and when it ends -- before any report, so what was learned is on
    disk whatever a report does. Every save replaces the file atomically, so after kill -9
    the file is the last complete save.

    ``predicates`` are always written (those named with ``--save-predicate``, and those of
    an extension whose environment the run uses); ``offered`` ones (the other extensions')
    only when some agent has the predicate: a plain agent's file says nothing of
    ``afford/6``."""

    def __init__(self, path: Path, predicates: Sequence[SavedPredicate],
                 every: SaveInterval | None = None,
                 offered: Sequence[SavedPredicate] = ()) -> None:
        self.path = path
        self.predicates = tuple(predicates)
        self.offered = tuple(offered)
        self.written: tuple[SavedPredicate, ...] = self.predicates  # by the last save
        self.every = every or SaveInterval()
        self.saves = 0
        self._cycles = 0
        self._last = time.monotonic()
        self._failed = False
        self._unsaved: dict[str, str] = {}  # agents whose facts a save left out, told once

    def start(self, run: RunContext) -> None:
        """The interval starts with the run."""
        self._last = time.monotonic()

    def after_cycle(self, run: RunContext, agent: Agent) -> None:
        """Save when the interval has passed; a failed save is a warning (said once), the
        run goes on and the next save tries again."""
        self._cycles += 1
        due = ((self.every.cycles is not None and self._cycles % self.every.cycles == 0) or
               (self.every.seconds is not None and
                time.monotonic() - self._last >= self.every.seconds))
        if not due:
            return
        try:
            self._tell_unsaved(run, self.save(run.system.agents))
        except OSError as error:
            if not self._failed:
                run.console.print(f"warning: cannot save beliefs to {self.path}: "
                                  f"{error.strerror or error}; will try again", markup=False)
            self._failed = True
        self._last = time.monotonic()

    def save(self, agents: Iterable[Agent]) -> Saved:
        """Write the saved predicates of ``agents`` now (the offered ones some agent has)."""
        group = list(agents)
        self.written = self.predicates + tuple(
            predicate for predicate in self.offered
            if any(_may_know(agent, predicate) for agent in group))
        saved = save_beliefs(group, self.written, self.path)
        self.saves += 1
        self._failed = False
        return saved

    def finish(self, run: RunContext) -> None:
        """Save and say how many beliefs of which predicates went where (and whose not)."""
        saved = self.save(run.system.agents)
        self._tell_unsaved(run, saved)
        which = ", ".join(predicate.indicator for predicate in self.written)
        if which:
            run.console.print(f"saved {saved.count} {which} beliefs to {self.path}",
                              markup=False)
        else:
            run.console.print(f"saved no beliefs to {self.path}: no agent has a predicate to "
                              "save (name one with --save-predicate NAME/ARITY)", markup=False)

    def _tell_unsaved(self, run: RunContext, saved: Saved) -> None:
        """A warning for each agent a save left out (once per agent and reason)."""
        for name, reason in saved.unsaved.items():
            if self._unsaved.get(name) != reason:
                run.console.print(f"warning: beliefs of agent {name} not saved to "
                                  f"{self.path}: {reason}", markup=False)
        self._unsaved.update(saved.unsaved)
