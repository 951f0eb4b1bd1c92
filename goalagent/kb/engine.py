"""The one SWI-Prolog engine of the process: syntax checks, term conversion, error mapping.

This is the ONLY module that imports pyswip. It uses pyswip just to load and initialise
``libswipl`` and then talks to the C foreign interface directly through ctypes (the string
API costs 40-80 µs a call; this path a few µs). Terms crossing the seam are
``goalagent.kb.terms`` values, converted in :meth:`Engine._put` / :meth:`Engine._get`.
Every query is opened, drained or cut, and closed inside one Python call, with
``debug_on_error`` off and exceptions caught, so Prolog never enters the tracer.
"""

from __future__ import annotations

import ctypes
import threading
from collections.abc import Callable, Sequence
from ctypes import POINTER, byref, c_char_p, c_double, c_int, c_int64, c_size_t, c_uint, c_void_p
from fractions import Fraction
from pathlib import Path

from pyswip import core as _pyswip_core  # loads libswipl and runs PL_initialise once

from goalagent.kb.errors import KBError, PrologRuntimeError, PrologSyntaxError
from goalagent.kb.terms import Atom, Struct, Term, Var, format_term

__all__ = [
    "Engine",
    "define_foreign",
    "Record",
    "KBError",
    "PrologRuntimeError",
    "PrologSyntaxError",
    "get_engine",
]


# --------------------------------------------------------------------------- C interface

_lib = ctypes.CDLL(_pyswip_core._lib._name, mode=ctypes.RTLD_GLOBAL)

_term = c_size_t
_atom = c_size_t


def _fn(name: str, restype: object, *argtypes: object) -> ctypes._CFuncPtr:
    """Our own typed handle on a libswipl function (pyswip's handles keep their own types)."""
    func = getattr(_lib, name)
    func.restype = restype
    func.argtypes = argtypes
    return func


PL_open_foreign_frame = _fn("PL_open_foreign_frame", c_size_t)
PL_discard_foreign_frame = _fn("PL_discard_foreign_frame", None, c_size_t)
PL_new_term_ref = _fn("PL_new_term_ref", _term)
PL_new_term_refs = _fn("PL_new_term_refs", _term, c_int)
PL_copy_term_ref = _fn("PL_copy_term_ref", _term, _term)
PL_predicate = _fn("PL_predicate", c_void_p, c_char_p, c_int, c_char_p)
PL_open_query = _fn("PL_open_query", c_void_p, c_void_p, c_int, c_void_p, _term)
PL_next_solution = _fn("PL_next_solution", c_int, c_void_p)
PL_cut_query = _fn("PL_cut_query", c_int, c_void_p)
PL_exception = _fn("PL_exception", _term, c_void_p)
PL_record = _fn("PL_record", c_void_p, _term)
PL_recorded = _fn("PL_recorded", c_int, c_void_p, _term)
PL_erase = _fn("PL_erase", None, c_void_p)
PL_term_type = _fn("PL_term_type", c_int, _term)
PL_get_atom = _fn("PL_get_atom", c_int, _term, POINTER(_atom))
PL_get_int64 = _fn("PL_get_int64", c_int, _term, POINTER(c_int64))
PL_get_float = _fn("PL_get_float", c_int, _term, POINTER(c_double))
PL_get_nchars = _fn("PL_get_nchars", c_int, _term, POINTER(c_size_t), POINTER(c_void_p), c_uint)
PL_get_name_arity = _fn("PL_get_name_arity_sz", c_int, _term, POINTER(_atom), POINTER(c_size_t))
PL_get_arg = _fn("_PL_get_arg_sz", c_int, c_size_t, _term, _term)
PL_get_list = _fn("PL_get_list", c_int, _term, _term, _term)
PL_compare = _fn("PL_compare", c_int, _term, _term)
PL_put_variable = _fn("PL_put_variable", c_int, _term)
PL_put_atom = _fn("PL_put_atom", c_int, _term, _atom)
PL_put_int64 = _fn("PL_put_int64", c_int, _term, c_int64)
PL_put_float = _fn("PL_put_float", c_int, _term, c_double)
PL_put_chars = _fn("PL_put_chars", c_int, _term, c_int, c_size_t, c_char_p)
PL_put_nil = _fn("PL_put_nil", c_int, _term)
PL_put_term = _fn("PL_put_term", c_int, _term, _term)
PL_put_term_from_chars = _fn("PL_put_term_from_chars", c_int, _term, c_int, c_size_t, c_char_p)
PL_cons_list = _fn("PL_cons_list", c_int, _term, _term, _term)
PL_cons_functor_v = _fn("PL_cons_functor_v", c_int, _term, c_size_t, _term)
PL_new_functor = _fn("PL_new_functor_sz", c_size_t, _atom, c_size_t)
PL_new_atom = _fn("PL_new_atom_mbchars", _atom, c_int, c_size_t, c_char_p)
PL_register_atom = _fn("PL_register_atom", None, _atom)
PL_unregister_atom = _fn("PL_unregister_atom", None, _atom)
PL_unify = _fn("PL_unify", c_int, _term, _term)
PL_raise_exception = _fn("PL_raise_exception", c_int, _term)
PL_register_foreign_in_module = _fn("PL_register_foreign_in_module", c_int, c_char_p,
                                    c_char_p, c_int, c_void_p, c_int)
PL_thread_self = _fn("PL_thread_self", c_int)
PL_thread_attach_engine = _fn("PL_thread_attach_engine", c_int, c_void_p)

_PL_VARIABLE, _PL_ATOM, _PL_INTEGER, _PL_RATIONAL, _PL_FLOAT, _PL_STRING = 1, 2, 3, 4, 5, 6
_PL_TERM, _PL_NIL, _PL_LIST_PAIR = 7, 8, 10
_Q_FLAGS = 0x04 | 0x08  # PL_Q_NODEBUG | PL_Q_CATCH_EXCEPTION
_REP_UTF8 = 0x00100000
_CVT_ATOM, _CVT_STRING, _CVT_INTEGER, _CVT_WRITEQ = 0x1, 0x2, 0x8, 0x200
_TEXT_FLAGS = _CVT_ATOM | _CVT_STRING | _REP_UTF8
_PUT_STRING = 6 | _REP_UTF8  # PL_STRING type for PL_put_chars
_INT64_MIN, _INT64_MAX = -(2**63), 2**63 - 1
_ATOM_CACHE_MAX = 200_000  # cached atoms stay registered (never GC'd): keep this bounded
_PARSE_CACHE_MAX = 20_000
_VAR_MARK = "$ga_var"

_SUPPORT = Path(__file__).with_name("mentalstate.pl")
_PYTHON_ERROR = "$ga_python"  # the Prolog exception that carries a Python one out of Prolog

# A foreign predicate of arity 2 as SWI calls it: foreign_t f(term_t a1, term_t a2).
_FOREIGN_2 = ctypes.CFUNCTYPE(c_size_t, _term, _term)


# Output buffers for the getters: Prolog runs on one thread at a time and every value is
# read right after the call that fills it, so one set of buffers serves all calls.
_ATOM_BUF, _SIZE_BUF, _INT_BUF, _FLOAT_BUF = _atom(), c_size_t(), c_int64(), c_double()
_ATOM_REF, _SIZE_REF = byref(_ATOM_BUF), byref(_SIZE_BUF)
_INT_REF, _FLOAT_REF = byref(_INT_BUF), byref(_FLOAT_BUF)


def _text(t: int, flags: int) -> str:
    """The text of an atom/string/number term (UTF-8) or raises on failure."""
    length = c_size_t()
    ptr = c_void_p()
    if not PL_get_nchars(t, byref(length), byref(ptr), flags):
        raise KBError("cannot read the text of a Prolog term")
    return ctypes.string_at(ptr.value, length.value).decode("utf-8")


class Record:
    """A Prolog term kept in Prolog (``PL_record``) until Python asks for its value: answers
    that are usually never read cost no conversion."""

    __slots__ = ("_engine", "_handle", "_value")

    def __init__(self, engine: Engine, handle: int) -> None:
        self._engine = engine
        self._handle: int | None = handle
        self._value: Term | None = None

    def value(self) -> Term:
        """The term as a Python value (converted once, then the record is freed)."""
        if self._handle is not None:
            self._value = self._engine._recorded(self._handle)
            PL_erase(self._handle)
            self._handle = None
        return self._value

    def __del__(self) -> None:
        """Frees the record at the engine's next call (from the thread that runs Prolog)."""
        if self._handle is not None:
            self._engine._dead_records.append(self._handle)


class Engine:
    """The process's SWI-Prolog: one per process (see :func:`get_engine`), one thread at a time."""

    def __init__(self) -> None:
        self._thread = threading.get_ident()
        self._atoms: dict[str, int] = {}
        self._atom_names: dict[int, Atom] = {}
        self._functors: dict[tuple[str, int], int] = {}
        self._functor_names: dict[int, str] = {}  # atom handle -> plain str (Struct names)
        self._preds: dict[tuple[str, int, str], int] = {}
        self._parsed: dict[str, Term] = {}
        self._transient_atoms: list[int] = []  # uncached atoms: unregistered after the call
        self._dead_records: list[int] = []  # records of collected Record objects, to erase
        self._counter = 0
        self._foreign: list[object] = []  # ctypes callbacks SWI holds: keep them alive
        self._python_errors: list[BaseException] = []  # raised inside foreign predicates
        self.call("set_prolog_flag", Atom("debug_on_error"), Atom("false"), module="system")
        self.call("set_prolog_flag", Atom("report_error"), Atom("false"), module="system")
        loaded = self.call(
            "load_files",
            Atom(str(_SUPPORT)),
            [Struct("silent", (Atom("true"),)), Struct("if", (Atom("not_loaded"),))],
            module="system",
        )
        if loaded is None:
            raise KBError(f"could not load {_SUPPORT}")

    # ------------------------------------------------------------------ public API

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

    def format(self, term: Term) -> str:
        """Prolog text for ``term`` (canonical, reads back as the same term)."""
        return format_term(term)

    def seed_random(self, seed: int) -> None:
        """Seeds Prolog's random generator (random/1, random_member/2, ...) for repeatable runs."""
        self.call("set_random", Struct("seed", (int(seed),)), module="system")

    def write(self, term: Term, *, quoted: bool = False) -> str:
        """``term`` as SWI's write/1 (or writeq/1) shows it: operators, lists, no quotes
        (with ``quoted``: quotes where needed) -- for print/log output meant for people."""
        result = self.call("write_text", term, Atom("true" if quoted else "false"), None)
        assert result is not None
        return str(result[2])

    # ------------------------------------------------------------------ calling Prolog

    def unique_name(self, prefix: str) -> str:
        """A fresh name (for modules and compiled conditions): ``prefix`` + counter."""
        self._counter += 1
        return f"{prefix}{self._counter}"

    def predicate(self, name: str, arity: int, module: str, *, cache: bool = True) -> int:
        """A predicate handle for ``module:name/arity`` (cached unless the module is an
        agent's: the caller keeps those, and they die with the module)."""
        key = (name, arity, module)
        handle = self._preds.get(key)
        if handle is None:
            handle = PL_predicate(name.encode(), arity, module.encode())
            if cache:
                self._preds[key] = handle
        return handle

    def forget_atom(self, name: str) -> None:
        """Drops ``name`` from the atom cache (e.g. a destroyed module) so Prolog can GC it."""
        handle = self._atoms.pop(name, None)
        if handle is not None:
            self._atom_names.pop(handle, None)
            PL_unregister_atom(handle)

    def call(self, name: str, *args: Term | None, module: str = "ga_kb", marks: bool = False,
             read: Sequence[int] | None = None) -> list[Term | None] | None:
        """Runs ``module:name(args)`` once; ``None`` args are fresh variables. Returns the
        arguments after the first solution (only the ``None`` ones, or those listed in
        ``read``, are read back from Prolog; the others are returned as given), or ``None``
        when the goal fails."""
        if read is None:
            read = [i for i, arg in enumerate(args) if arg is None]
        answers = self.solve(self.predicate(name, len(args), module), len(args),
                             list(enumerate(args)), 1, marks, read)
        if not answers:
            return None
        result: list[Term | None] = list(args)
        for index, value in zip(read, answers[0], strict=True):
            result[index] = value
        return result

    def solve(self, pred: int, arity: int, inputs: Sequence[tuple[int, Term | None]],
              limit: int | None, marks: bool = False,
              outputs: Sequence[int] | None = None, keep: int | None = None) -> list[list[Term]]:
        """All (or the first ``limit``) solutions of ``pred`` called with the given
        ``(argument index, value)`` inputs; each solution lists the values of the
        ``outputs`` arguments (default: all); output ``keep`` is not converted but kept as a
        :class:`Record`. ``marks``: see :meth:`_get`."""
        if threading.get_ident() != self._thread:
            self._attach_thread()
        if outputs is None:
            outputs = range(arity)
        fid = PL_open_foreign_frame()
        try:
            base = PL_new_term_refs(arity) if arity else PL_new_term_ref()
            shared: dict[str, int] = {}
            try:
                for index, value in inputs:
                    if value is not None:
                        self._put(base + index, value, shared)
            except UnicodeEncodeError as error:
                raise KBError(f"text Prolog cannot hold: {error.object!r}") from None
            qid = PL_open_query(None, _Q_FLAGS, pred, base)
            answers: list[list[Term]] = []
            record = None
            try:
                get = self._get
                while limit is None or len(answers) < limit:
                    if not PL_next_solution(qid):
                        exception = PL_exception(qid)
                        if exception:
                            record = PL_record(exception)
                        break
                    seen: list[tuple[int, Var]] = []
                    if keep is None:
                        answers.append([get(base + i, seen, marks) for i in outputs])
                    else:
                        answers.append([Record(self, PL_record(base + i)) if i == keep
                                        else get(base + i, seen, marks) for i in outputs])
            except (RecursionError, ctypes.ArgumentError) as error:
                if isinstance(error, ctypes.ArgumentError) and "Recursion" not in str(error):
                    raise
                raise KBError("an answer is a cyclic or too deeply nested term") from None
            finally:
                PL_cut_query(qid)
            if record is not None:
                error = self._runtime_error(record)
                if error.term == _PYTHON_ERROR and self._python_errors:
                    python_error = self._python_errors[-1]
                    self._python_errors.clear()
                    raise python_error
                raise error
            return answers
        finally:
            PL_discard_foreign_frame(fid)
            while self._transient_atoms:
                PL_unregister_atom(self._transient_atoms.pop())
            while self._dead_records:
                PL_erase(self._dead_records.pop())

    # ------------------------------------------------------------------ internals

    def _attach_thread(self) -> None:
        """Gives the calling thread a Prolog engine (pyswip is not thread-safe: one at a time)."""
        if PL_thread_self() == -1 and PL_thread_attach_engine(None) < 0:
            raise KBError("cannot attach a Prolog engine to this thread")
        self._thread = threading.get_ident()

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

    def _runtime_error(self, record: int) -> PrologRuntimeError:
        """Turns a recorded exception term into a PrologRuntimeError (SWI's message text)."""
        fid = PL_open_foreign_frame()
        try:
            t = PL_new_term_ref()
            PL_recorded(record, t)
            PL_erase(record)
            term = self._get(t, [], False)
            pred = self.predicate("error_message", 2, "ga_kb")
            base = PL_new_term_refs(2)
            PL_put_term(base, t)
            qid = PL_open_query(None, _Q_FLAGS, pred, base)
            try:
                ok = PL_next_solution(qid)
                message = _text(base + 1, _TEXT_FLAGS) if ok else format_term(term)
            finally:
                PL_cut_query(qid)
            return PrologRuntimeError(message, term)
        finally:
            PL_discard_foreign_frame(fid)

    def _recorded(self, record: int) -> Term:
        """The Python value of a recorded term (the record stays)."""
        if threading.get_ident() != self._thread:
            self._attach_thread()
        fid = PL_open_foreign_frame()
        try:
            t = PL_new_term_ref()
            PL_recorded(record, t)
            return self._get(t, [], False)
        finally:
            PL_discard_foreign_frame(fid)

    def _atom_handle(self, name: str) -> int:
        """The atom_t for ``name`` (cached and kept registered while the cache has room)."""
        handle = self._atoms.get(name)
        if handle is None:
            data = name.encode("utf-8")
            handle = PL_new_atom(_REP_UTF8, len(data), data)  # returned registered
            if len(self._atoms) < _ATOM_CACHE_MAX:
                self._atoms[name] = handle
                self._atom_names[handle] = Atom(name)
            else:
                self._transient_atoms.append(handle)
        return handle

    def _functor(self, name: str, arity: int) -> int:
        """The functor_t for name/arity (functors are never garbage collected: cache them)."""
        key = (name, arity)
        handle = self._functors.get(key)
        if handle is None:
            handle = PL_new_functor(self._atom_handle(name), arity)
            self._functors[key] = handle
        return handle

    def _put(self, t: int, value: Term, shared: dict[str, int]) -> None:
        """Stores the Python term ``value`` in term ref ``t``; ``shared`` maps Var names."""
        kind = type(value)
        if kind is Atom:
            handle = self._atoms.get(value)
            PL_put_atom(t, handle if handle is not None else self._atom_handle(value))
        elif kind is Struct:
            arity = len(value.args)
            if arity == 0:
                data = format_term(value).encode("utf-8")
                PL_put_term_from_chars(t, _REP_UTF8, len(data), data)
                return
            args = PL_new_term_refs(arity)
            put = self._put
            for i, arg in enumerate(value.args):
                put(args + i, arg, shared)
            functor = self._functors.get((value.name, arity))
            PL_cons_functor_v(t, functor or self._functor(value.name, arity), args)
        elif kind is int:
            if _INT64_MIN <= value <= _INT64_MAX:
                PL_put_int64(t, value)
            else:
                data = str(value).encode()
                PL_put_term_from_chars(t, _REP_UTF8, len(data), data)
        elif kind is list or kind is tuple:
            PL_put_nil(t)
            if value:
                head = PL_new_term_ref()
                put = self._put
                for item in reversed(value):
                    put(head, item, shared)
                    PL_cons_list(t, head, t)
        elif kind is Var:
            existing = shared.get(value.name) if value.name != "_" else None
            if existing is None:
                PL_put_variable(t)
                if value.name != "_":
                    shared[value.name] = PL_copy_term_ref(t)
            else:
                PL_put_term(t, existing)
        elif kind is float:
            PL_put_float(t, value)
        elif kind is bool:
            PL_put_atom(t, self._atom_handle("true" if value else "false"))
        elif isinstance(value, Atom):
            self._put(t, Atom(str(value)), shared)
        elif isinstance(value, str):
            data = value.encode("utf-8")
            PL_put_chars(t, _PUT_STRING, len(data), data)
        else:
            raise KBError(f"not a Prolog term: {value!r}")

    def _get(self, t: int, seen: list[tuple[int, Var]], marks: bool) -> Term:
        """The Python term in term ref ``t``; ``seen`` keeps unbound variables' identities;
        with ``marks``, ``'$ga_var'(Name)`` becomes ``Var(Name)`` (see parse/2)."""
        kind = PL_term_type(t)
        if kind == _PL_ATOM:
            PL_get_atom(t, _ATOM_REF)
            handle = _ATOM_BUF.value
            return self._atom_names.get(handle) or self._atom_name(handle)
        if kind == _PL_TERM:
            PL_get_name_arity(t, _ATOM_REF, _SIZE_REF)
            handle = _ATOM_BUF.value
            arity = _SIZE_BUF.value
            name = self._functor_names.get(handle)
            if name is None:
                name = str(self._atom_names.get(handle) or self._atom_name(handle))
                self._functor_names[handle] = name
            arg = PL_new_term_ref()
            args = []
            get = self._get
            for i in range(1, arity + 1):
                PL_get_arg(i, t, arg)
                args.append(get(arg, seen, marks))
            if marks and name == _VAR_MARK and arity == 1:
                return Var(str(args[0]))
            return Struct(name, tuple(args))
        if kind == _PL_INTEGER:
            if PL_get_int64(t, _INT_REF):
                return _INT_BUF.value
            return int(_text(t, _CVT_INTEGER))
        if kind == _PL_LIST_PAIR:
            items: list[Term] = []
            rest = PL_copy_term_ref(t)
            head = PL_new_term_ref()
            get = self._get
            while PL_get_list(rest, head, rest):
                items.append(get(head, seen, marks))
            if PL_term_type(rest) == _PL_NIL:
                return items
            tail = get(rest, seen, marks)
            for item in reversed(items):
                tail = Struct("[|]", (item, tail))
            return tail
        if kind == _PL_NIL:
            return []
        if kind == _PL_STRING:
            return _text(t, _TEXT_FLAGS)
        if kind == _PL_FLOAT:
            PL_get_float(t, _FLOAT_REF)
            return _FLOAT_BUF.value
        if kind == _PL_VARIABLE:
            for ref, var in seen:
                if PL_compare(ref, t) == 0:
                    return var
            self._counter += 1
            var = Var("_" if marks else f"_G{self._counter}")
            seen.append((PL_copy_term_ref(t), var))
            return var
        if kind == _PL_RATIONAL:
            numerator, denominator = _text(t, _CVT_WRITEQ | _REP_UTF8).split("r")
            return float(Fraction(int(numerator), int(denominator)))
        return Atom(_text(t, _CVT_WRITEQ | _REP_UTF8))  # blobs (streams, clause refs), dicts

    def _atom_name(self, handle: int) -> Atom:
        """The name of atom ``handle`` (cache miss path); caching registers the atom."""
        ref = PL_new_term_ref()
        PL_put_atom(ref, handle)
        name = Atom(_text(ref, _TEXT_FLAGS))
        if len(self._atom_names) < _ATOM_CACHE_MAX:
            PL_register_atom(handle)
            self._atom_names[handle] = name
            self._atoms.setdefault(str(name), handle)
        return name


def _copy(term: Term) -> Term:
    """A copy of ``term`` whose lists are fresh (cached parses must not be mutated)."""
    if isinstance(term, list):
        return [_copy(item) for item in term]
    if isinstance(term, Struct):
        return Struct(term.name, tuple(_copy(arg) for arg in term.args))
    return term


def define_foreign(engine: Engine, module: str, name: str,
                   respond: Callable[[Term], Term | None]) -> None:
    """Defines ``module:name(+Request, -Reply)``: Prolog's call converts Request to a Python
    term, calls ``respond`` and unifies Reply with its answer (None: leaves Reply unbound).
    A Python exception in ``respond`` leaves Prolog as the exception ``'$ga_python'`` and is
    raised again where Python called Prolog (:meth:`Engine.solve`)."""

    def foreign(request: int, reply: int) -> int:
        try:
            answer = respond(engine._get(request, [], False))
            if answer is None:
                return 1
            t = PL_new_term_ref()
            engine._put(t, answer, {})
            return 1 if PL_unify(reply, t) else 0
        except BaseException as error:  # noqa: BLE001 - carried out of Prolog, re-raised
            engine._python_errors.append(error)
            t = PL_new_term_ref()
            PL_put_atom(t, engine._atom_handle(_PYTHON_ERROR))
            return PL_raise_exception(t)

    callback = _FOREIGN_2(foreign)
    engine._foreign.append(callback)
    if not PL_register_foreign_in_module(module.encode(), name.encode(), 2,
                                         ctypes.cast(callback, c_void_p), 0):
        raise KBError(f"cannot define the foreign predicate {module}:{name}/2")


_engine: Engine | None = None
_engine_lock = threading.Lock()


def get_engine() -> Engine:
    """The process's engine, created (and SWI-Prolog set up) on first use."""
    global _engine
    with _engine_lock:
        if _engine is None:
            _engine = Engine()
        return _engine
