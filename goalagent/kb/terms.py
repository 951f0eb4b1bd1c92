"""Python values for Prolog terms: what queries return and what environments send.

Atoms are ``Atom`` (a ``str`` subclass, so ``Atom("a") == "a"``), Prolog strings are plain
``str``, numbers are ``int``/``float``, lists are ``list``, compounds are ``Struct`` and
unbound variables ``Var``. ``format_term`` writes any of them back as Prolog text that
SWI-Prolog reads as the same term (canonical form: never operator syntax).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass


class Atom(str):
    """A Prolog atom; compares equal to the Python string of its name."""

    __slots__ = ()

    def __repr__(self) -> str:
        return f"Atom({str.__repr__(self)})"


@dataclass(frozen=True)
class Var:
    """An unbound Prolog variable (name as in the source, or ``_G123``)."""

    name: str

    def __str__(self) -> str:
        return self.name


@dataclass(frozen=True)
class Struct:
    """A compound term ``name(args...)``."""

    name: str
    args: tuple[Term, ...]

    @property
    def arity(self) -> int:
        return len(self.args)

    def __str__(self) -> str:
        return format_term(self)


Term = Atom | str | int | float | Struct | Var | list

_LONG = 10**4000
_LETTER_ATOM = re.compile(r"[a-z][A-Za-z0-9_]*\Z")
_SYMBOL_ATOM = re.compile(r"[+\-*/\\^<>=~:.?@#&$]+\Z")


def quote_atom(name: str) -> str:
    """The atom's name as SWI-Prolog's ``writeq`` would write it (quoted when needed)."""
    if _LETTER_ATOM.match(name) or name in ("!", ";", "{}"):
        return name
    if _SYMBOL_ATOM.match(name) and name != "." and "/*" not in name:
        return name  # (a symbol atom holding /* would start a comment)
    escaped = name.replace("\\", "\\\\").replace("'", "\\'").replace("\n", "\\n")
    escaped = escaped.replace("\t", "\\t")
    return f"'{escaped}'"


def _format_float(value: float) -> str:
    if math.isnan(value):
        return "1.5NaN"
    if math.isinf(value):
        return "1.0Inf" if value > 0 else "-1.0Inf"
    text = repr(value)
    if "e" in text and "." not in text.split("e")[0]:
        mantissa, exponent = text.split("e")
        text = f"{mantissa}.0e{exponent}"
    return text


def format_term(term: Term) -> str:
    """Prolog text for ``term`` that reads back as the same term."""
    if isinstance(term, bool):
        return "true" if term else "false"
    if isinstance(term, Atom):
        return quote_atom(str(term))
    if isinstance(term, str):
        escaped = term.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
        return f'"{escaped}"'
    if isinstance(term, int):  # very long: hexadecimal (Python's str(int) has a limit)
        return str(term) if -_LONG < term < _LONG else format(term, "#x")
    if isinstance(term, float):
        return _format_float(term)
    if isinstance(term, Var):
        return term.name
    if isinstance(term, (list, tuple)):
        return "[" + ",".join(format_term(item) for item in term) + "]"
    if isinstance(term, Struct):
        if not term.args:
            return quote_atom(term.name) + "()"
        args = ",".join(format_term(arg) for arg in term.args)
        return f"{quote_atom(term.name)}({args})"
    raise TypeError(f"not a Prolog term: {term!r}")


MAX_INT_DIGITS = 100_000
"""The longest integer handed from Prolog to Python (SWI's are unbounded; converting decimal
text costs more than linear time, so a 10^10^7 computed by an agent is refused)."""
_CHUNK = 4000  # below Python's default limit for int(str)


def decimal_int(text: str) -> int:
    """The integer written in decimal ``text`` of any length up to MAX_INT_DIGITS (Python's
    ``int(str)`` refuses more than 4,300 digits; halves are converted and combined)."""
    digits = len(text) - text.startswith("-")
    if digits <= _CHUNK:
        return int(text)
    if digits > MAX_INT_DIGITS:
        raise ValueError(f"an integer of {digits} digits is too large to convert (at most "
                         f"{MAX_INT_DIGITS})")
    if text.startswith("-"):
        return -decimal_int(text[1:])
    low = len(text) // 2
    return decimal_int(text[:-low]) * 10**low + decimal_int(text[-low:])
