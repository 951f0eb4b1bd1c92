"""Helpers of the parser tests: the rules of a parsed program and their parts, compared
independent of layout."""

from __future__ import annotations

import re

from goalagent import ast
from goalagent.parser import parse_agent


def squash(text: str) -> str:
    """Prolog text without white space, to compare fragments independent of layout."""
    return re.sub(r"\s+", "", text)


def main_rules(program: ast.AgentProgram) -> tuple[ast.Rule, ...]:
    """The rules of the main module (which must exist)."""
    main = program.module("main")
    assert main is not None, "no main module"
    return main.rules


def one_rule(body: str) -> ast.Rule:
    """The single rule of a main module whose program section is ``body``."""
    rules = main_rules(parse_agent(f"main module {{ program {{ {body} }} }}"))
    assert len(rules) == 1
    return rules[0]


def literal_ops(condition: ast.Condition) -> list[str]:
    """The operators of a condition, ``not`` for a NotLiteral."""
    return ["not" if isinstance(lit, ast.NotLiteral) else lit.op for lit in condition]
