"""Python <-> Prolog terms over the C interface (the values of ``goalagent.kb.terms``): the
base of :class:`~goalagent.kb.engine.Engine`, kept apart so that each file has one job.

Written by hand rather than through pyswip's converters: these read and build terms with a
few C calls each and keep atom and functor handles cached (pyswip's string API costs
40-80 µs a call).
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction
from typing import Any

from goalagent.kb.clib import (
    ATOM_BUF,
    ATOM_REF,
    CVT_INTEGER,
    CVT_VARIABLE,
    CVT_WRITEQ,
    FLOAT_BUF,
    FLOAT_REF,
    INT64_MAX,
    INT64_MIN,
    INT_BUF,
    INT_REF,
    PL_ATOM,
    PL_FLOAT,
    PL_INTEGER,
    PL_LIST_PAIR,
    PL_NIL,
    PL_RATIONAL,
    PL_STRING,
    PL_TERM,
    PL_VARIABLE,
    PUT_STRING,
    REP_UTF8,
    SIZE_BUF,
    SIZE_REF,
    TEXT_FLAGS,
    PL_cons_functor_v,
    PL_cons_list,
    PL_copy_term_ref,
    PL_erase,
    PL_get_arg,
    PL_get_atom,
    PL_get_float,
    PL_get_int64,
    PL_get_list,
    PL_get_name_arity,
    PL_new_atom,
    PL_new_functor,
    PL_new_term_ref,
    PL_new_term_refs,
    PL_put_atom,
    PL_put_chars,
    PL_put_float,
    PL_put_int64,
    PL_put_nil,
    PL_put_term,
    PL_put_term_from_chars,
    PL_put_variable,
    PL_register_atom,
    PL_term_type,
    integer_bits,
    text_of,
)
from goalagent.kb.errors import KBError
from goalagent.kb.terms import (
    MAX_INT_DIGITS,
    Atom,
    Struct,
    Term,
    Var,
    decimal_int,
    format_term,
)

# The bits of the largest integer converted (decimal_int's digits, rounded up to limbs).
_MAX_INT_BITS = MAX_INT_DIGITS * 3322 // 1000 + 64


class Record:
    """A Prolog term kept in Prolog (``PL_record``) until Python asks for its value: answers
    that are usually never read cost no conversion."""

    __slots__ = ("_engine", "_handle", "_value")

    def __init__(self, engine: TermConversion, handle: int) -> None:
        self._engine = engine
        self._handle: int | None = handle
        self._value: Term | None = None

    def value(self) -> Term:
        """The term as a Python value (converted once, then the record is freed)."""
        if self._handle is not None:
            self._value = self._engine._recorded(self._handle)
            # Forgotten before it is erased: a signal's stop between the two leaves the
            # record unfreed, never erased twice (by __del__: SWI-Prolog aborts on that).
            handle, self._handle = self._handle, None
            PL_erase(handle)
        return self._value

    def __del__(self) -> None:
        """Frees the record at the engine's next call (from the thread that runs Prolog)."""
        try:
            handle = self._handle  # (set after _engine)
        except AttributeError:  # a signal's stop inside __init__: nothing to free
            return
        if handle is not None:
            self._engine._dead_records.append(handle)


ATOM_CACHE_MAX = 200_000  # cached atoms stay registered (never GC'd): keep this bounded
VAR_MARK = "$ga_var"  # parse/2 marks named variables as '$ga_var'(Name)


class TermConversion:
    """Puts Python terms into term refs and gets them back, with atom and functor handles
    cached."""

    def __init__(self) -> None:
        self._atoms: dict[str, int] = {}
        self._atom_names: dict[int, Atom] = {}
        self._functors: dict[tuple[str, int], int] = {}
        self._functor_names: dict[int, str] = {}  # atom handle -> plain str (Struct names)
        self._transient_atoms: list[int] = []  # uncached atoms: unregistered after the call
        self._dead_records: list[int] = []  # records of collected Record objects, to erase
        self._counter = 0
        self._putters: dict[type, Callable[[int, Any, dict[str, int]], None]] = {
            Atom: self._put_atom, Struct: self._put_compound, int: self._put_integer,
            list: self._put_list, tuple: self._put_list, Var: self._put_variable,
            float: self._put_float, bool: self._put_bool, str: self._put_string}
        self._getters: dict[int, Callable[[int, list[tuple[int, Var]], bool], Term]] = {
            PL_ATOM: self._get_atom, PL_TERM: self._get_compound, PL_INTEGER: self._get_integer,
            PL_LIST_PAIR: self._get_list, PL_NIL: self._get_nil, PL_STRING: self._get_string,
            PL_FLOAT: self._get_float, PL_VARIABLE: self._get_variable,
            PL_RATIONAL: self._get_rational}

    def _atom_handle(self, name: str) -> int:
        """The atom_t for ``name`` (cached and kept registered while the cache has room)."""
        handle = self._atoms.get(name)
        if handle is None:
            data = name.encode("utf-8")
            handle = PL_new_atom(REP_UTF8, len(data), data)  # returned registered
            if len(self._atoms) < ATOM_CACHE_MAX:
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

    # ------------------------------------------------------------------ Python -> Prolog
    # One function per kind of Python value, chosen by its exact type in ``_putters`` (a
    # table rather than a chain of tests: a compound puts each argument with one lookup).

    def _put_term(self, t: int, value: Term, shared: dict[str, int]) -> None:
        """Stores the Python term ``value`` in term ref ``t``; ``shared`` maps Var names."""
        self._putters.get(type(value), self._put_subclass)(t, value, shared)

    def _put_atom(self, t: int, value: Atom, shared: dict[str, int]) -> None:
        handle = self._atoms.get(value)
        PL_put_atom(t, handle if handle is not None else self._atom_handle(value))

    def _put_compound(self, t: int, value: Struct, shared: dict[str, int]) -> None:
        arity = len(value.args)
        if arity == 0:  # name(): no C call builds it, the reader does
            data = format_term(value).encode("utf-8")
            PL_put_term_from_chars(t, REP_UTF8, len(data), data)
            return
        args = PL_new_term_refs(arity)
        putters, other = self._putters, self._put_subclass
        for i, arg in enumerate(value.args):
            putters.get(type(arg), other)(args + i, arg, shared)
        functor = self._functors.get((value.name, arity))
        PL_cons_functor_v(t, functor or self._functor(value.name, arity), args)

    def _put_integer(self, t: int, value: int, shared: dict[str, int]) -> None:
        if INT64_MIN <= value <= INT64_MAX:
            PL_put_int64(t, value)
        else:  # hexadecimal: no digit limit, linear (Python's str(int) has neither)
            data = format(value, "#x").encode()
            PL_put_term_from_chars(t, REP_UTF8, len(data), data)

    def _put_list(self, t: int, value: list[Term] | tuple[Term, ...],
                  shared: dict[str, int]) -> None:
        PL_put_nil(t)
        if value:
            head = PL_new_term_ref()
            putters, other = self._putters, self._put_subclass
            for item in reversed(value):
                putters.get(type(item), other)(head, item, shared)
                PL_cons_list(t, head, t)

    def _put_variable(self, t: int, value: Var, shared: dict[str, int]) -> None:
        existing = shared.get(value.name) if value.name != "_" else None
        if existing is None:
            PL_put_variable(t)
            if value.name != "_":
                shared[value.name] = PL_copy_term_ref(t)
        else:
            PL_put_term(t, existing)

    def _put_float(self, t: int, value: float, shared: dict[str, int]) -> None:
        PL_put_float(t, value)

    def _put_bool(self, t: int, value: bool, shared: dict[str, int]) -> None:
        PL_put_atom(t, self._atom_handle("true" if value else "false"))

    def _put_string(self, t: int, value: str, shared: dict[str, int]) -> None:
        data = value.encode("utf-8")
        PL_put_chars(t, PUT_STRING, len(data), data)

    def _put_subclass(self, t: int, value: object, shared: dict[str, int]) -> None:
        """A value of no type of the table: a subclass of Atom or str, or not a term."""
        if isinstance(value, Atom):
            self._put_atom(t, Atom(str(value)), shared)
        elif isinstance(value, str):
            self._put_string(t, value, shared)
        else:
            raise KBError(f"not a Prolog term: {value!r}")

    # ------------------------------------------------------------------ Prolog -> Python
    # One function per kind of Prolog term (PL_term_type), chosen in ``_getters``; ``seen``
    # keeps unbound variables' identities; with ``marks``, ``'$ga_var'(Name)`` becomes
    # ``Var(Name)`` (see parse/2).

    def _get_term(self, t: int, seen: dict[str, Var], marks: bool) -> Term:
        """The Python term in term ref ``t``."""
        return self._getters.get(PL_term_type(t), self._get_other)(t, seen, marks)

    def _get_atom(self, t: int, seen: dict[str, Var], marks: bool) -> Term:
        PL_get_atom(t, ATOM_REF)
        handle = ATOM_BUF.value
        return self._atom_names.get(handle) or self._atom_name(handle)

    def _get_compound(self, t: int, seen: dict[str, Var], marks: bool) -> Term:
        PL_get_name_arity(t, ATOM_REF, SIZE_REF)
        handle = ATOM_BUF.value
        arity = SIZE_BUF.value
        name = self._functor_names.get(handle)
        if name is None:
            name = str(self._atom_names.get(handle) or self._atom_name(handle))
            self._functor_names[handle] = name
        arg = PL_new_term_ref()
        args = []
        getters, other = self._getters, self._get_other
        for i in range(1, arity + 1):
            PL_get_arg(i, t, arg)
            args.append(getters.get(PL_term_type(arg), other)(arg, seen, marks))
        if marks and name == VAR_MARK and arity == 1:
            return Var(str(args[0]))
        return Struct(name, tuple(args))

    def _get_integer(self, t: int, seen: dict[str, Var], marks: bool) -> Term:
        if PL_get_int64(t, INT_REF):
            return INT_BUF.value
        if integer_bits(t) > _MAX_INT_BITS:  # (not written out first: seconds for one)
            raise KBError(f"an integer of more than {MAX_INT_DIGITS:,} digits is too "
                          "large to convert")
        try:
            return decimal_int(text_of(t, CVT_INTEGER))
        except ValueError as error:
            raise KBError(str(error)) from None

    def _get_list(self, t: int, seen: dict[str, Var], marks: bool) -> Term:
        items: list[Term] = []
        rest = PL_copy_term_ref(t)
        head = PL_new_term_ref()
        getters, other = self._getters, self._get_other
        while PL_get_list(rest, head, rest):
            items.append(getters.get(PL_term_type(head), other)(head, seen, marks))
        if PL_term_type(rest) == PL_NIL:
            return items
        tail = self._get_term(rest, seen, marks)  # a partial list: [a, b | T]
        for item in reversed(items):
            tail = Struct("[|]", (item, tail))
        return tail

    def _get_nil(self, t: int, seen: dict[str, Var], marks: bool) -> Term:
        return []

    def _get_string(self, t: int, seen: dict[str, Var], marks: bool) -> Term:
        return text_of(t, TEXT_FLAGS)

    def _get_float(self, t: int, seen: dict[str, Var], marks: bool) -> Term:
        PL_get_float(t, FLOAT_REF)
        return FLOAT_BUF.value

    def _get_variable(self, t: int, seen: dict[str, Var], marks: bool) -> Term:
        # Known by the name SWI-Prolog writes for it, from its address: one look-up a
        # variable (comparing each with every one seen before took 178 s for 10,000).
        name = text_of(t, CVT_VARIABLE | REP_UTF8)
        var = seen.get(name)
        if var is None:
            self._counter += 1
            var = seen[name] = Var("_" if marks else f"_G{self._counter}")
        return var

    def _get_rational(self, t: int, seen: dict[str, Var], marks: bool) -> Term:
        numerator, denominator = text_of(t, CVT_WRITEQ | REP_UTF8).split("r")
        return float(Fraction(int(numerator), int(denominator)))

    def _get_other(self, t: int, seen: dict[str, Var], marks: bool) -> Term:
        """Blobs (streams, clause refs) and dicts: their quoted text, as an atom."""
        return Atom(text_of(t, CVT_WRITEQ | REP_UTF8))

    def _atom_name(self, handle: int) -> Atom:
        """The name of atom ``handle`` (cache miss path); caching registers the atom."""
        ref = PL_new_term_ref()
        PL_put_atom(ref, handle)
        name = Atom(text_of(ref, TEXT_FLAGS))
        if len(self._atom_names) < ATOM_CACHE_MAX:
            PL_register_atom(handle)
            self._atom_names[handle] = name
            self._atoms.setdefault(str(name), handle)
        return name
