"""`.mas2g` multi-agent system files of every GOAL version: the environment with its init
parameters, the agents (GOAL 4/5 agent files, GOAL 6+ agent definitions) and the launch
policy. The agents' programs are loaded by ``goalagent.parser.agents``."""

from __future__ import annotations

from pathlib import Path

from goalagent import ast
from goalagent.kb.engine import get_engine
from goalagent.kb.terms import Struct, Var, format_term
from goalagent.parser.ast_builder import build
from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.source import read_program_file


def parse_mas(text: str, file: str = "<string>") -> ast.MasProgram:
    """Parse the text of a `.mas2g` multi-agent system file. What GOAL's validator only
    warns about (a second agent file of one name, a launch rule naming no agent, an empty
    env, a duplicate init key, ...) is a warning of the program, not an error."""
    sections, builder = build(text, file, "mas")
    warn = builder.warn
    environment: str | None = None
    env_pos: ast.Pos | None = None
    env_init: list[tuple[str, ast.PrologText]] = []
    agentfiles: list[ast.AgentFile] = []
    definitions: list[ast.AgentDefinition] = []
    launches: list[ast.LaunchRule] = []
    sections_seen: dict[str, ast.Pos] = {}
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
            environment, env_pos = _environment(section, env_init, warn)
        elif kind == "agentfiles":
            sections_seen["agentfiles"] = section[2]
            for agentfile in section[1]:
                if any(a.name == agentfile.name for a in agentfiles):
                    warn(agentfile.pos, f"a second agent file called {agentfile.name}; "
                         "the first is used")
                    continue
                agentfiles.append(agentfile)
        else:
            sections_seen["launchpolicy"] = section[2]
            launches.extend(section[1])
    names = [a.name for a in agentfiles] + [d.name for d in definitions]
    for definition in definitions:
        if names.count(definition.name) > 1:
            raise GoalSyntaxError.at(definition.pos, f"there are two agents called "
                                     f"{definition.name}")
    known = [rule for rule in launches if rule.agentfile in names]
    for rule in launches:
        if rule.agentfile not in names:
            warn(rule.pos, f"launch refers to unknown agent {rule.agentfile!r} (no agent file "
                 f"or definition has that name; known: {', '.join(sorted(names)) or 'none'}); "
                 "it launches nothing")
    _warn_unused(agentfiles, known, environment, sections_seen, warn)
    first = ast.Pos(file, 1, 1)
    return ast.MasProgram(file, environment, tuple(env_init), tuple(agentfiles),
                          tuple(known), first, tuple(definitions), env_pos,
                          warnings=tuple(builder.warnings))


def _environment(section, env_init: list, warn) -> tuple[str | None, ast.Pos | None]:
    """GOAL 4/5's environment section: its env (None for ``env = ""``, which GOAL warns
    about) and init parameters (added to ``env_init``; a key given twice: the first)."""
    environment, env_pos = None, None
    named = False
    for key, value, key_pos in section[1]:
        if key == "env":
            named = True
            name = get_engine().parse_term(value.text)
            if not isinstance(name, str):
                raise GoalSyntaxError.at(value.pos, "env must name an environment "
                                         "(an atom or a string)")
            if not name:
                warn(key_pos, 'env = "" names no environment; the system runs without one')
                continue
            environment, env_pos = str(name), key_pos
        elif key == "init":
            for init_key, init_value in _init_pairs(value):
                if any(init_key == k for k, _ in env_init):
                    warn(init_value.pos, f"init parameter {init_key} is given twice; the "
                         "first is used")
                    continue
                env_init.append((init_key, init_value))
        else:
            raise GoalSyntaxError.at(key_pos, f"unknown environment key {key!r} (env, init)")
    if not named:
        raise GoalSyntaxError.at(section[2], "the environment section names no environment: "
                                 'write env = "name".')
    return environment, env_pos


def _warn_unused(agentfiles: list[ast.AgentFile], launches: list[ast.LaunchRule],
                 environment: str | None, sections: dict[str, ast.Pos], warn) -> None:
    """GOAL's warnings about a launch policy: empty sections, agent files no rule
    launches, an environment no conditional rule connects an agent to."""
    if "agentfiles" in sections and not agentfiles:
        warn(sections["agentfiles"], "the agentfiles section names no agent file")
    if "launchpolicy" in sections and not launches:
        warn(sections["launchpolicy"], "the launch policy launches no agent")
    if launches:
        for agentfile in agentfiles:
            if not any(rule.agentfile == agentfile.name for rule in launches):
                warn(agentfile.pos, f"agent file {agentfile.path} ({agentfile.name}) is "
                     "never launched")
    if environment and launches and not any(rule.on_entity for rule in launches):
        warn(launches[0].pos, "the system has an environment but no conditional launch "
             "rule (when ... do launch): no agent is connected to an entity")


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
        if not isinstance(key, (str, Var)) or not str(key):
            raise GoalSyntaxError.at(value.pos, f"init key {format_term(key)} is not a name")
        pairs.append((str(key), ast.PrologText(format_term(item.args[1]), value.pos)))
    return tuple(pairs)
