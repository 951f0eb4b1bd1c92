"""The one SWI-Prolog engine of the process: start-up, syntax checks, parsing and writing
terms, on top of the calls both ways (calls.py).

pyswip loads and initialises ``libswipl`` (see clib.py, the only module that imports it);
the engine then talks to the C foreign interface directly through ctypes (the string API
costs 40-80 µs a call; this path a few µs). Terms crossing the seam are
``goalagent.kb.terms`` values, converted in conversion.py (the base of calls.py's
``PrologCalls``). Every query is opened, drained or cut, and closed inside one Python call,
with ``debug_on_error`` off and exceptions caught, so Prolog never enters the tracer.
"""

from __future__ import annotations

import threading
from pathlib import Path

from goalagent.kb.calls import PrologCalls
from goalagent.kb.clib import (
    PL_discard_foreign_frame,
    PL_new_term_ref,
    PL_open_foreign_frame,
    PL_record,
)
from goalagent.kb.conversion import Kept, Record
from goalagent.kb.errors import KBError, PrologRuntimeError, PrologSyntaxError
from goalagent.kb.terms import Atom, Struct, Term, format_term

__all__ = [
    "Engine",
    "Kept",
    "Record",
    "KBError",
    "PrologRuntimeError",
    "PrologSyntaxError",
    "get_engine",
]


_PARSE_CACHE_MAX = 20_000
_SUPPORT = Path(__file__).with_name("mentalstate.pl")
_GUARD = Path(__file__).with_name("guard.pl")  # depth limits, files of facts, limits
_CONFINE = Path(__file__).with_name("confine.pl")  # what agents' Prolog may call
_MEMORY = Path(__file__).with_name("memory.pl")  # what an agent's memory holds
_SIZES = Path(__file__).with_name("sizes.pl")  # what one built-in call may make


# What launching an agent calls that runs none of its code (so draws no random number):
# its modules made, its limits, its conditions compiled or copied, its declarations, its
# directory; loading and adopting (load/6, adopt_checked/6) give a pending seed themselves
# when they run agent code (PrologModules, GoalBases; load_imaged/7 loads programs that
# run none).
_RUN_NO_AGENT_CODE = (
    ("new_agent", 2, "ga_kb"), ("set_limits", 3, "ga_guard"), ("compile", 6, "ga_kb"),
    ("clone_conditions", 6, "ga_kb"), ("declare", 4, "ga_kb"), ("declare_actions", 2, "ga_kb"),
    ("directory_add", 2, "ga_kb"), ("join_directory", 3, "ga_kb"), ("load", 6, "ga_kb"),
    ("load_imaged", 7, "ga_kb"), ("declare_imaged", 5, "ga_kb"), ("adopt_checked", 6, "ga_kb"),
)


class Engine(PrologCalls):
    """The process's SWI-Prolog: one per process (see :func:`get_engine`), one thread at a time."""

    def __init__(self) -> None:
        super().__init__()
        self._parsed: dict[str, Term] = {}
        self.call("set_prolog_flag", Atom("debug_on_error"), Atom("false"), module="system")
        self.call("set_prolog_flag", Atom("report_error"), Atom("false"), module="system")
        for support in (_CONFINE, _SUPPORT, _GUARD, _MEMORY, _SIZES):
            loaded = self.call(
                "load_files",
                Atom(str(support)),
                [Struct("silent", (Atom("true"),)), Struct("if", (Atom("not_loaded"),))],
                module="system",
            )
            if loaded is None:
                raise KBError(f"could not load {support}")
        for name, arity, module in _RUN_NO_AGENT_CODE:
            self.runs_no_agent_code(name, arity, module)

    def check_clause(self, text: str) -> tuple[str, ...]:
        """Checks one clause (no final '.') with SWI's reader; returns its variable names."""
        return self._check(text, "clause")

    def check_query(self, text: str) -> tuple[str, ...]:
        """Checks one goal or term (no final '.') with SWI's reader; returns its variable names."""
        return self._check(text, "query")

    def parse_term(self, text: str) -> Term:
        """The term in ``text``: named variables become ``Var(name)``, ``_`` ``Var('_')``."""
        return _copy(self.parsed(text))

    def parsed(self, text: str) -> Term:
        """As :meth:`parse_term`, but the shared cached term: callers must not mutate it."""
        cached = self._parsed.get(text)
        if cached is None:
            self.check_query(text)
            result = self.call("parse", text, None, marks=True)
            if result is None:
                raise KBError(f"cannot parse {text!r}")
            cached = result[1]
            if len(self._parsed) < _PARSE_CACHE_MAX:
                self._parsed[text] = cached
        return cached

    def keep(self, term: Term) -> Kept:
        """``term`` recorded in Prolog, to be given to calls as it is (see :class:`Kept`)."""
        self.guarded += 1
        try:
            fid = PL_open_foreign_frame()
            try:
                t = PL_new_term_ref()
                self._put_term(t, term, {})
                return Kept(self, PL_record(t))
            finally:
                PL_discard_foreign_frame(fid)
        finally:
            self.guarded -= 1
            self._stop_if_asked()

    def format(self, term: Term) -> str:
        """Prolog text for ``term`` (canonical, reads back as the same term)."""
        return format_term(term)

    def write(self, term: Term, *, quoted: bool = False) -> str:
        """``term`` as SWI's write/1 (or writeq/1) shows it: operators, lists, no quotes
        (with ``quoted``: quotes where needed) -- for print/log output meant for people."""
        result = self.call("write_text", term, Atom("true" if quoted else "false"), None)
        assert result is not None
        return str(result[2])

    def unique_name(self, prefix: str) -> str:
        """A fresh name (for modules and compiled conditions): ``prefix`` + counter."""
        self._counter += 1
        return f"{prefix}{self._counter}"

    def _check(self, text: str, kind: str) -> tuple[str, ...]:
        """Reads ``text`` as a clause or query with SWI's reader (see check/3 in the .pl)."""
        if not isinstance(text, str):
            raise KBError(f"Prolog text expected, got {text!r}")
        result = self.call("check", text, Atom(kind), None)
        if result is None:
            raise KBError(f"cannot check {text!r}")
        outcome = result[2]
        assert isinstance(outcome, Struct)
        if outcome.name == "ok":
            return tuple(str(name) for name in outcome.args[0])
        message, offset = str(outcome.args[0]), int(outcome.args[1])
        stripped = text.rstrip()
        if stripped.endswith(".") and offset >= len(stripped) - 1:
            offset = len(stripped) - 1
            message += " (leave out the final '.')"
        raise PrologSyntaxError(message, offset)


def _copy(term: Term) -> Term:
    """A copy of ``term`` whose lists are fresh (cached parses must not be mutated)."""
    if isinstance(term, list):
        return [_copy(item) for item in term]
    if isinstance(term, Struct):
        return Struct(term.name, tuple(_copy(arg) for arg in term.args))
    return term


_engine: Engine | None = None
_engine_lock = threading.Lock()


def get_engine() -> Engine:
    """The process's engine, created (and SWI-Prolog set up) on first use."""
    global _engine
    with _engine_lock:
        if _engine is None:
            _engine = Engine()
        return _engine
