"""Prolog as GOAL programs write it, read by SWI-Prolog 9: `not (p)`, `not p`, the atom table."""

from __future__ import annotations

import io

from goalagent.agent import Agent


def run_once(program: str) -> list[str]:
    agent = Agent.from_string(program, "compat.goal", output=io.StringIO())
    agent.step()
    return agent.output.getvalue().split()


def test_not_with_a_space_and_without_parentheses_is_negation():
    assert run_once("""
        init module { beliefs { p. r :- fail. } knowledge { q :- not (r). } }
        main module { program [order=linearall] {
            if bel(not (r), q) then print(spaced).
            if bel(not r) then print(bare).
            if bel(not p) then print(wrong).
            if bel(not(r)) then print(plain).
        } }
    """) == ["spaced", "bare", "plain"]


def test_table_is_an_ordinary_atom():
    assert run_once("""
        init module { beliefs { on(a, table). } }
        main module { program { if bel(on(X, Y), Y == table) then print(X). } }
    """) == ["a"]
