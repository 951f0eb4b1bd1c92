"""Per-agent cost of many mental states in one process (not a test): create, cycle, close.

Run: .venv/bin/python bench/kb_agents_scale.py [agents]   (default 10000)
Prints µs per agent for each fifth of the agents, so growth with the agent count shows.
"""

from __future__ import annotations

import resource
import sys
import time

from goalagent import ast
from goalagent.kb import MentalState

POS = ast.Pos("<bench>", 1, 1)


def text(source: str) -> ast.PrologText:
    """A PrologText at a dummy position."""
    return ast.PrologText(source, POS)


KNOWLEDGE = [
    text("clear(table)"),
    text("clear(X) :- block(X), \\+ on(_, X)"),
    text("tower([X]) :- on(X, table)"),
    text("tower([X, Y | T]) :- on(X, Y), tower([Y | T])"),
]
BELIEFS = [text(f"block({b})") for b in "abc"] + [text(f"on({b}, table)") for b in "abc"]
RULES = [
    (ast.MentalLiteral("a-goal", text("tower([X, Y | T])"), POS),
     ast.MentalLiteral("bel", text("tower([Y | T]), clear(X), clear(Y)"), POS)),
    (ast.MentalLiteral("a-goal", text("tower([X | _])"), POS),
     ast.MentalLiteral("bel", text("clear(X), not(on(X, table))"), POS)),
]


def rss_mb() -> float:
    """Peak resident memory of this process in MB."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def main(count: int) -> None:
    """Creates ``count`` blocks-world agents, runs one rule pass over all, closes them."""
    start_rss = rss_mb()
    states = []
    step = max(count // 5, 1)
    lap = start = time.perf_counter()
    for i in range(count):
        state = MentalState(f"agent{i}", knowledge=KNOWLEDGE, beliefs=BELIEFS)
        state.declare_updates(["on(X, Y)"])
        state.adopt("on(a, b), on(b, c), on(c, table)")
        for rule in RULES:
            state.solutions(state.compile(rule))
        states.append(state)
        if (i + 1) % step == 0:
            now = time.perf_counter()
            print(f"agents {i + 1:6d}: {(now - lap) / step * 1e6:6.0f} µs/agent to create")
            lap = now
    created = time.perf_counter()
    for state in states:
        for rule in RULES:
            state.solutions(state.compile(rule))
        state.blind_commitment()
    cycled = time.perf_counter()
    grown = rss_mb() - start_rss
    for state in states:
        state.close()
    closed = time.perf_counter()
    print(f"create {(created - start) / count * 1e6:.0f} µs/agent, "
          f"one rule pass {(cycled - created) / count * 1e6:.1f} µs/agent, "
          f"close {(closed - cycled) / count * 1e6:.0f} µs/agent, "
          f"memory {grown:.0f} MB ({grown * 1024 / count:.1f} KB/agent)")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 10_000)
