"""Files of facts (``--load-beliefs``): read and checked by SWI-Prolog, kept in Prolog, added
to agents' beliefs in one call each.

The whole file is read by SWI's own reader in one call (guard.pl's ``read_facts/4``): every
clause must be a ground fact -- a directive is refused, never run; rules, variables,
control constructs, module qualification, built-in or reserved predicates and terms nested
deeper than the runtime converts are refused -- and the first bad clause is reported at its
``file:line:col``. The facts stay in Prolog (a global variable of the engine) until
:meth:`FactFile.close`, so loading them into many agents converts nothing to Python; only
the checks a caller gives (e.g. the types of afford/6's arguments) run in Prolog too.
"""

from __future__ import annotations

import bisect
import re
from collections.abc import Sequence
from dataclasses import dataclass

from goalagent.ast import Pos
from goalagent.kb.engine import Engine, KBError, get_engine
from goalagent.kb.terms import Atom, Struct, Term, format_term

__all__ = ["FactCheck", "FactFile", "FactFileError", "FactWatch", "read_facts"]


class FactFileError(KBError):
    """A clause of a file of facts that is refused (or that an agent cannot take), at
    ``pos``; ``reason`` says why."""

    pos: Pos  # (always known, unlike other KBErrors')

    def __init__(self, pos: Pos, reason: str) -> None:
        super().__init__(f"{pos}: {reason}", pos)
        self.reason = reason


@dataclass(frozen=True)
class FactCheck:
    """What facts matching ``template`` must satisfy: ``condition`` (Prolog over the
    template's variables, e.g. ``integer(Tot), Tot >= 0``), which ``meaning`` puts in words
    for the error message."""

    template: str
    condition: str
    meaning: str


class FactFile:
    """The checked facts of one file, held in Prolog until closed."""

    def __init__(self, engine: Engine, key: Atom, lines: _Lines, count: int) -> None:
        self._engine = engine
        self.key = key
        self.file = lines.file
        self.pos = lines.pos  # character offset -> Pos
        self.count = count  # clauses in the file (duplicates included)
        self.closed = False

    def close(self) -> None:
        """Frees the facts kept in Prolog."""
        if not self.closed:
            self._engine.call("forget_facts", self.key, module="ga_guard")
            self.closed = True

    def __enter__(self) -> FactFile:
        """``with read_facts(...) as facts:`` frees them at the end of the block."""
        return self

    def __exit__(self, *exc: object) -> None:
        """Frees the facts (see :meth:`close`)."""
        self.close()


class _Lines:
    """Character offset -> ``file:line:col`` for one text (line starts found once)."""

    def __init__(self, file: str, text: str) -> None:
        self.file = file
        self.starts = [0] + [match.end() for match in re.finditer("\n", text)]

    def pos(self, offset: int) -> Pos:
        line = bisect.bisect_right(self.starts, offset)
        return Pos(self.file, line, offset - self.starts[line - 1] + 1, offset)


def read_facts(text: str, file: str, checks: Sequence[FactCheck] = (),
               engine: Engine | None = None) -> FactFile:
    """Reads and checks the facts of ``text`` (the content of ``file``); every fact that
    matches a check's template must satisfy its condition. A bad clause raises
    :class:`FactFileError` at its ``file:line:col`` saying what is wrong."""
    engine = engine or get_engine()
    key = Atom(engine.unique_name("$ga_facts"))
    texts = [f"'$check'(({check.template}), ({check.condition}), "
             f"{format_term(check.meaning)})" for check in checks]
    result = engine.call("read_facts", text, key, texts, None, module="ga_guard")
    assert result is not None and isinstance(result[3], Struct)
    outcome = result[3]
    lines = _Lines(file, text)
    if outcome.name == "error":
        offset, message = outcome.args
        raise FactFileError(lines.pos(int(offset)), str(message))  # type: ignore[arg-type]
    return FactFile(engine, key, lines, int(outcome.args[0]))  # type: ignore[arg-type]


class FactWatch:
    """Follows one predicate's facts in an agent's beliefs: :meth:`changes` says which were
    gained and lost since the last look, comparing in Prolog, so a report that follows
    100,000 facts converts only those that changed."""

    def __init__(self, engine: Engine, module: Atom, name: str, arity: int) -> None:
        self._engine = engine
        self._module = module
        self.name = name
        self.arity = arity
        self._key = Atom(engine.unique_name("$ga_watch"))
        self.closed = False

    def changes(self) -> tuple[list[Term], list[Term]]:
        """(gained, lost) facts since the last call (the first call: every fact gained)."""
        if self.closed:
            raise KBError(f"the watch of {self.name}/{self.arity} is closed")
        result = self._engine.call("fact_changes", self._module, self._key, Atom(self.name),
                                   self.arity, None, None, module="ga_guard")
        assert result is not None
        return result[4], result[5]  # type: ignore[return-value]

    def close(self) -> None:
        """Forgets the facts seen."""
        if not self.closed:
            self._engine.call("forget_facts", self._key, module="ga_guard")
            self.closed = True
