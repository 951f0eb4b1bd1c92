"""The knowledge-representation layer: the only part of goalagent that talks to SWI-Prolog.

- ``engine.py``: the process's one SWI-Prolog (``get_engine()``): syntax checks with SWI's own
  reader (``check_clause``/``check_query`` -> variable names, ``PrologSyntaxError.offset``),
  ``parse_term``, ``write``; on ``calls.py`` (queries, errors, foreign predicates: Prolog
  calling Python), ``stretches.py`` (where the main thread is, for the watchdog and the
  run's signal handler) and ``conversion.py`` (the Python <-> Prolog term conversion, raw C
  interface).
- ``mentalstate.py`` + ``mentalstate*.pl``: ``MentalState``, one agent's knowledge, beliefs,
  goal bases, percepts and mailbox in two private Prolog modules, joined from one part per
  job: ``prolog_modules.py`` (the modules, loaded and freed), ``conditions.py``,
  ``beliefbase.py``, ``goalbases.py``, ``percepts_and_mail.py``, ``identity.py``.
- ``interpreter.py`` + ``rules.pl``: the one rule interpreter; ``CompiledProgram`` compiles
  a program's rules and runs module passes in one call, asking its ``Requests`` for what
  only Python does.
- ``errors.py``: ``KBError`` and its kinds.

Typical use::

    state = MentalState("robot", knowledge=program.knowledge, beliefs=program.beliefs)
    state.declare_updates(formulas_of_all_inserts_deletes_posts_and_goals)
    state.adopt("on(a, b), on(b, table)")
    condition = state.compile(rule.condition)     # once per condition
    for answer in state.solutions(condition, {"X": Atom("a")}, limit=1):
        state.insert("not(on(X, Y)), on(X, table)", answer)
    state.blind_commitment()
    # or a whole program's rules, run by the interpreter (see goalagent.agent.rules):
    code = CompiledProgram(state, program)
    plan = code.plan([(program.module("main"), {})], environment=False, listen=False)
    outcome = code.run(plan, requests)
    state.close()

Errors are ``KBError`` (``PrologSyntaxError``, ``PrologRuntimeError`` with SWI's message).
"""

from goalagent.kb.conditions import CompiledCondition
from goalagent.kb.engine import (
    Engine,
    KBError,
    PrologRuntimeError,
    PrologSyntaxError,
    get_engine,
)
from goalagent.kb.mentalstate import MentalState
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
