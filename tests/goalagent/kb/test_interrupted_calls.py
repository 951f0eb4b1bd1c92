"""A signal's stop raised wherever the run's handler may raise it (goalagent/runner.py: not
while a call into SWI-Prolog is in progress, ``engine.depth`` or ``engine.guarded``) leaves
the engine whole: no query left open, no frame left undiscarded, and the next query answers.
Raised between opening a query and noting it, the stop used to leave the query open, and the
run then hung in its next query (the stop message's)."""

from __future__ import annotations

from goalagent.kb import Atom, Struct, get_engine
from tests.interrupt_points import Stop, interrupt_at

KB_FILES = ("goalagent/kb/calls.py", "goalagent/kb/engine.py", "goalagent/kb/conversion.py")


def test_a_stop_at_any_point_the_handler_may_raise_leaves_prolog_answering() -> None:
    engine = get_engine()
    may_raise = lambda: not (engine.depth or engine.guarded)  # noqa: E731 - the handler's test
    point = 0
    stopped = 0
    while True:
        point += 1
        with interrupt_at(point, KB_FILES, may_raise) as seen:
            try:
                answer = engine.call("atom_length", Atom("hello"), None, module="system")
                assert answer is not None and answer[1] == 5
                kept = engine.keep(Struct("f", (Atom("a"),)))
                assert engine.call("=", kept, None, module="system") is not None
            except Stop:
                stopped += 1
        assert (engine.depth, engine.guarded, engine.pending_stop) == (0, 0, None), point
        answer = engine.call("atom_length", Atom("abc"), None, module="system")
        assert answer is not None and answer[1] == 3, point
        if seen[0] < point:
            break
    assert stopped == point - 1 > 5  # stops came at every point the handler may raise
