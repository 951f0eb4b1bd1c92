"""Times MentalState.solutions() for a 2-literal condition (µs per call): not a test.

Run: .venv/bin/python bench/kb_solutions_timing.py
"""

from __future__ import annotations

import time

from goalagent import ast
from goalagent.kb import Atom, MentalState

POS = ast.Pos("<bench>", 1, 1)


def text(source: str) -> ast.PrologText:
    """A PrologText at a dummy position."""
    return ast.PrologText(source, POS)


def per_call(function, repeat: int = 20_000) -> float:
    """Best-of-5 mean µs per call of ``function``."""
    best = float("inf")
    for _ in range(5):
        start = time.perf_counter()
        for _ in range(repeat):
            function()
        best = min(best, (time.perf_counter() - start) / repeat * 1e6)
    return best


def main() -> None:
    """Blocks world: the condition a-goal(on(X, Y)), bel(clear(X)) with and without X bound."""
    blocks = "abcdefgh"
    state = MentalState(
        "bench",
        knowledge=[text("clear(X) :- block(X), \\+ on(_, X)"), text("clear(table)")],
        beliefs=[text(f"block({b})") for b in blocks]
        + [text(f"on({b}, table)") for b in blocks],
    )
    state.adopt("on(a, b), on(b, c), on(c, table)")
    condition = (
        ast.MentalLiteral("a-goal", text("on(X, Y)"), POS),
        ast.MentalLiteral("bel", text("clear(X)"), POS),
    )
    compiled = state.compile(condition)
    all_answers = per_call(lambda: state.solutions(compiled))
    first = per_call(lambda: state.solutions(compiled, limit=1))
    bound = per_call(lambda: state.solutions(compiled, {"X": Atom("b")}))
    single = (ast.MentalLiteral("bel", text("on(a, table)"), POS),)
    compiled_single = state.compile(single)
    yes_no = per_call(lambda: state.solutions(compiled_single))
    print(f"answers: {state.solutions(compiled)}")
    print(f"solutions(), 2 literals, all answers : {all_answers:6.1f} µs/call")
    print(f"solutions(), 2 literals, limit=1     : {first:6.1f} µs/call")
    print(f"solutions(), 2 literals, X bound     : {bound:6.1f} µs/call")
    print(f"solutions(), 1 ground literal        : {yes_no:6.1f} µs/call")
    insert = per_call(lambda: (state.insert("seen(a)"), state.delete("seen(a)")), 5_000)
    print(f"insert + delete of one fact          : {insert:6.1f} µs/pair")
    state.close()


if __name__ == "__main__":
    main()
