"""`.mas2g` multi-agent system files: the environment with its init parameters, the agent
files and the launch policy."""

from __future__ import annotations

from pathlib import Path

from goalagent import ast
from goalagent.kb.engine import get_engine
from goalagent.kb.terms import Struct, format_term
from goalagent.parser.ast_builder import build
from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.source import read_program_file


def parse_mas(text: str, file: str = "<string>") -> ast.MasProgram:
    """Parse the text of a `.mas2g` multi-agent system file."""
    sections, _ = build(text, file, "mas")
    environment = None
    env_init: tuple[tuple[str, ast.PrologText], ...] = ()
    agentfiles: list[ast.AgentFile] = []
    launches: list[ast.LaunchRule] = []
    for kind, items, _ in sections:  # type: ignore[attr-defined]
        if kind == "environment":
            for key, value, key_pos in items:
                if key == "env":
                    environment = str(get_engine().parse_term(value.text))
                elif key == "init":
                    env_init = _init_pairs(value)
                else:
                    raise GoalSyntaxError.at(key_pos, f"unknown environment key {key!r} "
                                             "(env, init)")
        elif kind == "agentfiles":
            agentfiles.extend(items)
        else:
            launches.extend(items)
    known = {a.name for a in agentfiles}
    for rule in launches:
        if rule.agentfile not in known:
            raise GoalSyntaxError.at(rule.pos, f"launch refers to unknown agent file "
                                     f"{rule.agentfile!r}; known: {', '.join(sorted(known))}")
    first = sections[0][2] if sections else ast.Pos(file, 1, 1)  # type: ignore[index]
    return ast.MasProgram(file, environment, env_init, tuple(agentfiles), tuple(launches), first)


def parse_mas_file(path: str | Path) -> ast.MasProgram:
    """Parse a `.mas2g` file."""
    return parse_mas(read_program_file(path), str(path))


def _init_pairs(value: ast.PrologText) -> tuple[tuple[str, ast.PrologText], ...]:
    """``[key = value, ...]`` as (key, value text) pairs, each value kept as Prolog text."""
    term = get_engine().parse_term(value.text)
    if not isinstance(term, list):
        raise GoalSyntaxError.at(value.pos, "init must be a list [key = value, ...]")
    pairs = []
    for item in term:
        if not (isinstance(item, Struct) and item.name == "=" and item.arity == 2):
            raise GoalSyntaxError.at(value.pos,
                                     f"init entry {format_term(item)} is not key = value")
        key = item.args[0]
        pairs.append((str(key), ast.PrologText(format_term(item.args[1]), value.pos)))
    return tuple(pairs)
