"""Helpers of the mental-state tests: literals and texts at one position, a blocks-world
knowledge base, and the values of a variable across answers."""

from __future__ import annotations

from goalagent import ast
from goalagent.kb import Atom, Struct

POS = ast.Pos("test.goal", 3, 5, 40)


def text(source: str, pos: ast.Pos = POS) -> ast.PrologText:
    return ast.PrologText(source, pos)


def lit(op: str, source: str | None = None) -> ast.MentalLiteral:
    return ast.MentalLiteral(op, text(source) if source is not None else None, POS)  # type: ignore[arg-type]


def neg(*literals: ast.Literal) -> ast.NotLiteral:
    return ast.NotLiteral(tuple(literals), POS)


def a(name: str) -> Atom:
    return Atom(name)


def on(x: str, y: str) -> Struct:
    return Struct("on", (Atom(x), Atom(y)))


BLOCKS_KNOWLEDGE = [
    text("block(a)"),
    text("block(b)"),
    text("block(c)"),
    text("clear(table)"),
    text("clear(X) :- block(X), \\+ on(_, X)"),
    text("tower([X]) :- on(X, table)"),
    text("tower([X, Y | T]) :- on(X, Y), tower([Y | T])"),
]


def values(answers: list[dict], name: str) -> list:
    return [answer[name] for answer in answers]
