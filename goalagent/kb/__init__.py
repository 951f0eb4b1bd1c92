"""The knowledge-representation layer: the only part of goalagent that talks to SWI-Prolog."""

from goalagent.kb.engine import (
    Engine,
    KBError,
    PrologRuntimeError,
    PrologSyntaxError,
    get_engine,
)
from goalagent.kb.mentalstate import CompiledCondition, MentalState
from goalagent.kb.terms import Atom, Struct, Term, Var, format_term

__all__ = [
    "Atom",
    "CompiledCondition",
    "Engine",
    "KBError",
    "MentalState",
    "PrologRuntimeError",
    "PrologSyntaxError",
    "Struct",
    "Term",
    "Var",
    "format_term",
    "get_engine",
]
