"""`.mas2g` multi-agent system files of every GOAL version: the environment with its init
parameters, the agents (GOAL 4/5 agent files, GOAL 6+ agent definitions) and the launch
policy. The agents' programs are loaded by ``goalagent.parser.agents``."""

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
    environment: str | None = None
    env_pos: ast.Pos | None = None
    env_init: list[tuple[str, ast.PrologText]] = []
    agentfiles: list[ast.AgentFile] = []
    definitions: list[ast.AgentDefinition] = []
    launches: list[ast.LaunchRule] = []
    for section in sections:  # type: ignore[attr-defined]
        if isinstance(section, ast.AgentDefinition):
            definitions.append(section)
            continue
        kind = section[0]
        if kind == "use":
            _, use, pairs, pos = section
            if environment is not None:
                raise GoalSyntaxError.at(pos, "a second environment; a system has one")
            environment, env_pos = use.ref, use.pos
            env_init.extend((key, value) for key, value, _ in pairs)
        elif kind == "environment":
            for key, value, key_pos in section[1]:
                if key == "env":
                    name = get_engine().parse_term(value.text)
                    if not isinstance(name, str) or not name:
                        raise GoalSyntaxError.at(value.pos, "env must name an environment "
                                                 "(an atom or a string)")
                    environment = str(name)
                    env_pos = key_pos
                elif key == "init":
                    env_init.extend(_init_pairs(value))
                else:
                    raise GoalSyntaxError.at(key_pos, f"unknown environment key {key!r} "
                                             "(env, init)")
        elif kind == "agentfiles":
            agentfiles.extend(section[1])
        else:
            launches.extend(section[1])
    names = [a.name for a in agentfiles] + [d.name for d in definitions]
    for name in names:
        if names.count(name) > 1:
            where = next(a.pos for a in (*agentfiles, *definitions) if a.name == name)
            raise GoalSyntaxError.at(where, f"there are two agents called {name}")
    for rule in launches:
        if rule.agentfile not in names:
            raise GoalSyntaxError.at(rule.pos, f"launch refers to unknown agent "
                                     f"{rule.agentfile!r} (no agent file or definition has "
                                     f"that name); known: {', '.join(sorted(names))}")
    first = ast.Pos(file, 1, 1)
    return ast.MasProgram(file, environment, tuple(env_init), tuple(agentfiles),
                          tuple(launches), first, tuple(definitions), env_pos)


def parse_mas_file(path: str | Path) -> ast.MasProgram:
    """Parse a `.mas2g` file."""
    return parse_mas(read_program_file(path), str(path))


def _init_pairs(value: ast.PrologText) -> tuple[tuple[str, ast.PrologText], ...]:
    """``[key = value, ...]`` as (key, value text) pairs, each value kept as Prolog text;
    a key written with a capital (``Floors = 10``) is that name, not a variable."""
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
