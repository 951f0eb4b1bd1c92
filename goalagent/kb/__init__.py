"""The knowledge-representation layer: the only part of goalagent that talks to SWI-Prolog.

- ``engine.py``: the process's one SWI-Prolog (``get_engine()``): syntax checks with SWI's own
  reader (``check_clause``/``check_query`` -> variable names, ``PrologSyntaxError.offset``),
  ``parse_term``, ``write`` and the Python <-> Prolog term conversion (raw C interface).
- ``mentalstate.py`` + ``mentalstate.pl``: ``MentalState``, one agent's knowledge, beliefs,
  goal bases, percepts and mailbox in two private Prolog modules.

Typical use::

    state = MentalState("robot", knowledge=program.knowledge, beliefs=program.beliefs)
    state.declare_updates(formulas_of_all_inserts_deletes_posts_and_goals)
    state.adopt("on(a, b), on(b, table)")
    rule = state.compile(rule.condition)          # once per rule
    for answer in state.solutions(rule, {"X": Atom("a")}, limit=1):
        state.insert("not(on(X, Y)), on(X, table)", answer)
    state.blind_commitment()
    # or, the condition and the leading actions in one call (see MentalState.compile_rule):
    compiled = state.compile_rule("if", rule, [("insert", "done(X)")])
    firings = state.fire(compiled)                # firings.actions, firings.items()
    state.close()

Errors are ``KBError`` (``PrologSyntaxError``, ``PrologRuntimeError`` with SWI's message).
"""

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
