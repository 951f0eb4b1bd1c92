"""Arithmetic errors are Prolog's, at run time, where the arithmetic runs (GOAL on
SWI-Prolog): a knowledge clause whose arithmetic cannot work (an atom as a number, a
division by zero) loads, as SWI consults it, and costs nothing while nobody calls it; a
condition that reaches it is a Prolog error in that rule -- a located warning, the rule
not applicable -- and the other rules go on. However the runtime compiles conditions and
knowledge, an error SWI could find when compiling must not refuse the program."""

from __future__ import annotations

import io

from goalagent.agent import Agent

PROGRAM = """init module { knowledge {
    never(X) :- X is foo + 1.
    halves(X, Y) :- Y is X / 0.
    cmp :- 1 < a.
    folded(X) :- X is 1 / 0.
  }
  beliefs { n(1). } }
main module [exit=always] { program {
    if bel(n(N), M is N + zork) then print(M).
    if bel(n(N), halves(N, Y)) then print(Y).
    if bel(cmp) then print(cmp).
    if bel(folded(X)) then print(X).
    if bel(n(N), M is N * 2 + 1) then print(M).
} }
"""


def test_arithmetic_errors_are_run_time_warnings_in_their_rules():
    warnings: list[str] = []
    output = io.StringIO()
    agent = Agent.from_string(PROGRAM, "arith.goal", output=output, warn=warnings.append)
    try:
        report = agent.step()
    finally:
        agent.close()
    assert output.getvalue() == "3\n"
    assert report.actions == ["print(3)"]
    expected = [
        (9, "is/2: Arithmetic: `zork/0' is not a function"),
        (10, "//2: Arithmetic: evaluation error: `zero_divisor'"),
        (11, "Arithmetic: `a/0' is not a function"),
        (12, "//2: Arithmetic: evaluation error: `zero_divisor'"),
    ]
    assert warnings == [f"warning: agent arith: module main, rule at arith.goal:{line}:5: "
                        f"Prolog error in the condition: {message}; the rule is not applicable"
                        for line, message in expected]
