"""Interface-level terms (EIS parameters, percepts, actions) and their Prolog counterparts.

The mapping to ``goalagent.kb.terms`` values (and through ``format_term`` to Prolog text):

=====================  ===========================================================
EIS                    Prolog / kb term
=====================  ===========================================================
``Identifier(v)``      atom ``v`` (``Atom``); quoted as needed, e.g. ``'Hello world'``
``Identifier(v,        string ``"v"`` (plain ``str``); the flag keeps strings lossless
string=True)``
``Numeral(n)``         integer or float, exactly as given (``1`` and ``1.0`` differ)
``Function(f, ps)``    compound ``f(p1, ..., pn)`` (``Struct``); ``f()`` when ``ps`` is empty
``ParameterList(ps)``  proper list ``[p1, ..., pn]``
``TruthValue(b)``      atom ``true`` / ``false`` (read back as an ``Identifier``)
=====================  ===========================================================

Prolog terms read through ``from_term`` come back exactly (``to_term(from_term(t)) == t``),
with two caveats inherited from the kb term model: an unbound variable has no EIS form and is
refused with ``TranslationException`` (percepts and actions must be ground), and ``Atom("[]")``
formats as ``[]``, which SWI-Prolog reads as the empty list.

``to_parameter`` is a separate, shorthand reader for Python values written by environment code:
there a plain ``str`` is an identifier (atom), ``bool`` a truth value and a tuple a list.
``to_python`` goes the other way for environment code: like ``to_term`` but truth values
become ``bool``.

A ``Percept`` or ``Action`` is converted once, into what its reader takes: a percept an
environment wrote as a term or shorthand (``percept_from_term``, ``Percept.of``) keeps the
term, checked and made canonical in one pass, and reaches the agent as it is instead of
being taken apart into parameters and built again; an agent's action (``action_from_term``)
gets its parameters, which the environment reads. Either makes the other form only if
something asks for it.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import FrozenInstanceError, dataclass, field
from typing import TypeVar

from goalagent.eis.exceptions import TranslationException
from goalagent.kb.terms import Atom, Struct, Term, Var, format_term


@dataclass(frozen=True)
class Identifier:
    """A name: a Prolog atom, or a Prolog string when ``string`` is true."""

    value: str
    string: bool = False

    def __post_init__(self) -> None:
        if not isinstance(self.value, str):
            raise TypeError(f"Identifier needs a str, got {self.value!r}")

    def __str__(self) -> str:
        return format_term(to_term(self))


@dataclass(frozen=True, eq=False)
class Numeral:
    """An integer or float, compared exactly as Prolog does (``1`` vs ``1.0``, ``0.0``/``-0.0``)."""

    value: int | float

    def __post_init__(self) -> None:
        if isinstance(self.value, bool) or not isinstance(self.value, (int, float)):
            raise TypeError(f"Numeral needs an int or float, got {self.value!r}")

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Numeral) or type(self.value) is not type(other.value):
            return False
        if isinstance(self.value, int):
            return self.value == other.value
        if math.isnan(self.value):
            return math.isnan(other.value)
        same_sign = math.copysign(1.0, self.value) == math.copysign(1.0, other.value)
        return self.value == other.value and same_sign

    def __hash__(self) -> int:
        return hash((type(self.value), self.value))

    def __str__(self) -> str:
        return format_term(self.value)


def _checked_params(owner: str, params: Iterable[Parameter]) -> tuple[Parameter, ...]:
    """``params`` as a tuple, each checked to be a Parameter (``owner`` names the type)."""
    items = tuple(params)
    for item in items:
        if not isinstance(item, _PARAMETER_TYPES):
            raise TypeError(
                f"{owner} parameters must be EIS parameters, got {item!r} "
                "(use to_parameter() to convert Python values)"
            )
    return items


def _params_tuple(owner: object, params: Iterable[Parameter]) -> None:
    """Store ``params`` on a frozen dataclass as a tuple, checking each is a Parameter."""
    object.__setattr__(owner, "params", _checked_params(type(owner).__name__, params))


@dataclass(frozen=True)
class Function:
    """A named function of parameters: a Prolog compound term."""

    name: str
    params: tuple[Parameter, ...] = field(default=())

    def __post_init__(self) -> None:
        _params_tuple(self, self.params)

    def __str__(self) -> str:
        return format_term(to_term(self))


@dataclass(frozen=True)
class ParameterList:
    """An ordered list of parameters: a Prolog list."""

    params: tuple[Parameter, ...] = field(default=())

    def __post_init__(self) -> None:
        _params_tuple(self, self.params)

    def __str__(self) -> str:
        return format_term(to_term(self))


@dataclass(frozen=True)
class TruthValue:
    """A boolean: the Prolog atom ``true`` or ``false``."""

    value: bool

    def __post_init__(self) -> None:
        if not isinstance(self.value, bool):
            raise TypeError(f"TruthValue needs a bool, got {self.value!r}")

    def __str__(self) -> str:
        return "true" if self.value else "false"


Parameter = Identifier | Numeral | Function | ParameterList | TruthValue
_PARAMETER_TYPES = (Identifier, Numeral, Function, ParameterList, TruthValue)


_N = TypeVar("_N", bound="_Named")


class _Named:
    """``name(params...)``: what percepts and actions have in common (an atom without
    parameters). They stay two types, as in EIS, so one is never taken for the other.

    Each keeps the kb term it was made from or stands for, so a term crossing the seam is
    converted once: one made from a term (an environment's percept, an agent's action)
    builds its parameters only when something reads them, one made from parameters builds
    its term only when something asks for it. Immutable, compared by name and parameters.
    """

    __slots__ = ("name", "_params", "_term")
    name: str
    _params: tuple[Parameter, ...] | None  # None until read, for one made from a term
    _term: Term | None  # None until asked for, for one made from parameters

    def __init__(self, name: str, params: Iterable[Parameter] = ()) -> None:
        object.__setattr__(self, "name", name)
        object.__setattr__(self, "_params", _checked_params(type(self).__name__, params))
        object.__setattr__(self, "_term", None)

    @classmethod
    def _of_term(cls: type[_N], name: str, term: Term) -> _N:
        """One standing for ``term``, already ground and canonical (``_canonical_term``)."""
        named = cls.__new__(cls)
        object.__setattr__(named, "name", name)
        object.__setattr__(named, "_params", None)
        object.__setattr__(named, "_term", term)
        return named

    @classmethod
    def of(cls: type[_N], name: str, *values: object) -> _N:
        """One from Python shorthand values (see ``to_parameter``)."""
        try:
            terms = [_shorthand_term(value) for value in values]
        except _KeptAsParameters:
            return cls(name, tuple(to_parameter(value) for value in values))
        return cls._of_term(name, _named_term(name, terms))

    @classmethod
    def _from_term(cls: type[_N], term: Term, what: str, *, parameters: bool) -> _N:
        """One for an atom or compound term (``f()`` reads as the atom ``f``), keeping the
        term, or (``parameters``: for a reader of parameters) its parameters."""
        if isinstance(term, Atom):
            return cls._of_term(str(term), term if type(term) is Atom else Atom(str(term)))
        if isinstance(term, Struct):
            if not term.args:
                return cls._of_term(term.name, Atom(term.name))
            if not parameters:
                try:
                    return cls._of_term(term.name, _canonical_term(term))
                except _KeptAsParameters:
                    pass
            return cls(term.name, tuple(from_term(arg) for arg in term.args))
        if isinstance(term, Var):
            raise TranslationException(
                f"{what} is an unbound variable {term.name}; it must be ground")
        shown = format_term(term) if isinstance(term, (str, int, float, list)) else repr(term)
        raise TranslationException(f"{what} must be an atom or a compound term, got {shown}")

    @property
    def params(self) -> tuple[Parameter, ...]:
        """The parameters (made from the term on first use)."""
        params = self._params
        if params is None:
            term = self._term
            params = tuple(from_term(arg) for arg in term.args) if type(term) is Struct else ()
            object.__setattr__(self, "_params", params)
        return params

    @property
    def term(self) -> Term:
        """The kb term: an atom when there are no parameters, else a compound."""
        term = self._term
        if term is None:
            assert self._params is not None  # (one of the two is always there)
            term = _named_term(self.name, [to_term(param) for param in self._params])
            object.__setattr__(self, "_term", term)
        return term

    def __setattr__(self, name: str, value: object) -> None:
        raise FrozenInstanceError(f"cannot assign to field {name!r}")

    def __delattr__(self, name: str) -> None:
        raise FrozenInstanceError(f"cannot delete field {name!r}")

    def __eq__(self, other: object) -> bool:
        if other.__class__ is not self.__class__:
            return NotImplemented
        return self.name == other.name and self.params == other.params  # type: ignore

    def __hash__(self) -> int:
        return hash((self.name, self.params))

    def __repr__(self) -> str:
        return f"{type(self).__name__}(name={self.name!r}, params={self.params!r})"

    def __reduce__(self) -> tuple[type, tuple[str, tuple[Parameter, ...]]]:
        return type(self), (self.name, self.params)

    def __str__(self) -> str:
        return format_term(self.term)


class Percept(_Named):
    """What an entity perceives."""

    __slots__ = ()


class Action(_Named):
    """What an agent asks an entity to do."""

    __slots__ = ()


def _unbound(var: Var) -> TranslationException:
    return TranslationException(
        f"unbound variable {var.name} cannot be sent to or from an environment "
        "(percepts and actions must be ground)"
    )


def _not_shorthand(value: object) -> TranslationException:
    return TranslationException(
        f"cannot turn {value!r} ({type(value).__name__}) into an EIS parameter; use str, int, "
        "float, bool, list/tuple, a kb term or an EIS parameter"
    )


def to_term(param: Parameter) -> Term:
    """The kb term (and so Prolog term) for an EIS parameter."""
    if isinstance(param, Identifier):
        return param.value if param.string else Atom(param.value)
    if isinstance(param, Numeral):
        return param.value
    if isinstance(param, TruthValue):
        return Atom("true" if param.value else "false")
    if isinstance(param, ParameterList):
        return [to_term(item) for item in param.params]
    if isinstance(param, Function):
        return Struct(param.name, tuple(to_term(item) for item in param.params))
    raise TypeError(f"not an EIS parameter: {param!r}")


def from_term(term: Term) -> Parameter:
    """The EIS parameter for a kb term; an unbound variable raises ``TranslationException``."""
    if isinstance(term, bool):
        return TruthValue(term)
    if isinstance(term, Atom):
        return Identifier(str(term))
    if isinstance(term, str):
        return Identifier(term, string=True)
    if isinstance(term, (int, float)):
        return Numeral(term)
    if isinstance(term, (list, tuple)):
        return ParameterList(tuple(from_term(item) for item in term))
    if isinstance(term, Struct):
        return Function(term.name, tuple(from_term(arg) for arg in term.args))
    if isinstance(term, Var):
        raise _unbound(term)
    raise TranslationException(f"not a Prolog term: {term!r}")


def to_parameter(value: object) -> Parameter:
    """An EIS parameter from a Python shorthand value: str is an atom, tuple/list a list."""
    if isinstance(value, _PARAMETER_TYPES):
        return value
    if isinstance(value, bool):
        return TruthValue(value)
    if isinstance(value, (int, float)):
        return Numeral(value)
    if isinstance(value, str):
        return Identifier(str(value))
    if isinstance(value, (list, tuple)):
        return ParameterList(tuple(to_parameter(item) for item in value))
    if isinstance(value, (Struct, Var)):
        return from_term(value)
    raise _not_shorthand(value)


def to_python(param: Parameter) -> Term:
    """A plain Python value for a parameter: atoms as ``Atom``, functions as ``Struct``."""
    if isinstance(param, TruthValue):
        return param.value
    if isinstance(param, ParameterList):
        return [to_python(item) for item in param.params]
    if isinstance(param, Function):
        return Struct(param.name, tuple(to_python(item) for item in param.params))
    return to_term(param)


class _KeptAsParameters(Exception):
    """A value only EIS parameters hold as given: a Python ``bool`` (a ``TruthValue``, which
    a term would make the atom ``true`` or ``false``) or an EIS parameter itself."""


def _shorthand_term(value: object) -> Term:
    """The kb term of a Python shorthand value, as ``to_term(to_parameter(value))`` but
    without building the parameter: str is an atom, tuple/list a list, a kb term as
    :func:`_canonical_term` makes it."""
    if isinstance(value, (bool, *_PARAMETER_TYPES)):
        raise _KeptAsParameters
    if isinstance(value, (int, float)):
        return value
    if isinstance(value, str):
        return value if type(value) is Atom else Atom(str(value))
    if isinstance(value, (list, tuple)):
        return [_shorthand_term(item) for item in value]
    if isinstance(value, (Struct, Var)):
        return _canonical_term(value)
    raise _not_shorthand(value)


def _canonical_term(term: Term) -> Term:
    """The kb term as EIS carries it, ``to_term(from_term(term))`` without building the
    parameters: the same object where nothing changes (a ground term of atoms, numbers,
    strings and compounds), tuples as lists; an unbound variable raises
    ``TranslationException``."""
    kind = type(term)
    if kind is Atom or kind is int or kind is float or kind is str:
        return term
    if kind is Struct:
        args = term.args  # type: ignore[union-attr]
        canonical = tuple(_canonical_term(arg) for arg in args)
        if all(new is old for new, old in zip(canonical, args, strict=True)):
            return term
        return Struct(term.name, canonical)  # type: ignore[union-attr]
    if isinstance(term, bool):
        raise _KeptAsParameters
    if isinstance(term, Atom):
        return Atom(str(term))
    if isinstance(term, (str, int, float)):
        return term
    if isinstance(term, (list, tuple)):
        return [_canonical_term(item) for item in term]
    if isinstance(term, Struct):
        return Struct(term.name, tuple(_canonical_term(arg) for arg in term.args))
    if isinstance(term, Var):
        raise _unbound(term)
    raise TranslationException(f"not a Prolog term: {term!r}")


def _named_term(name: str, args: list[Term]) -> Term:
    """``name(args...)``, or the atom ``name`` without arguments."""
    return Struct(name, tuple(args)) if args else Atom(name)


def percept_to_term(percept: Percept) -> Term:
    """The Prolog term for a percept: an atom when it has no parameters, else a compound."""
    return percept.term


def percept_from_term(term: Term) -> Percept:
    """The percept for an atom or compound term (``f()`` reads as the atom ``f``): it keeps
    the term, which is what its reader, an agent, takes."""
    return Percept._from_term(term, "a percept", parameters=False)


def action_to_term(action: Action) -> Term:
    """The Prolog term for an action: an atom when it has no parameters, else a compound."""
    return action.term


def action_from_term(term: Term) -> Action:
    """The action for an atom or compound term as an agent's program sends it (ground): its
    parameters, which is what its reader, an environment, takes."""
    return Action._from_term(term, "an action", parameters=True)
