"""Agents of a `.mas2g` system as ``ast.AgentProgram``s, whatever format they are written
in: a GOAL 4/5 agent file (`.goal`), or a GOAL 6+ agent definition whose init, main and
event modules are `.mod2g` files that ``use`` knowledge, belief and goal files (`.pl`),
action specifications (`.act2g`) and other modules. Both formats end in the same program
model, so everything after the parser runs them alike.

A reference is resolved as GOAL does: relative to the file that names it, a dotted name
being a path (``MapAgent.MapAgentInit`` is ``MapAgent/MapAgentInit.mod2g``), the extension
following from how it is used. The newest dialect (``use m for decisions.``) reads bare
condition literals as belief queries, sends actions that no specification declares to the
environment, and turns its percept rules (``replace p/1.``) into event rules.
"""

from __future__ import annotations

import difflib
import glob
from dataclasses import replace
from pathlib import Path
from typing import Any

from goalagent import ast
from goalagent.kb.engine import get_engine
from goalagent.parser.ast_builder import build
from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.goal_file import finish_program, parse_agent
from goalagent.parser.module_sections import ActionFile, ModuleFile
from goalagent.parser.reparse import parsed_once
from goalagent.parser.source import read_program_file

_EXTENSIONS = {
    "knowledge": (".pl",), "beliefs": (".pl",), "goals": (".pl",),
    "actionspec": (".act2g",), "module": (".mod2g",), "main": (".mod2g",),
    "event": (".mod2g",), "init": (".mod2g",), "decisions": (".mod2g",),
    "updates": (".mod2g",), "mas": (".mas2g",), None: (".mod2g", ".act2g", ".pl"),
}
_KNOWN_SUFFIXES = (".pl", ".mod2g", ".act2g", ".mas2g", ".goal", ".test2g", ".jar")
_ROLES = {"init": "init", "main": "main", "event": "event", "decisions": "main",
          "updates": "event"}


def resolve_reference(use: ast.UseClause, base: Path) -> Path:
    """The file a use clause names, relative to the folder ``base`` of the naming file."""
    ref = use.ref
    if not use.quoted:
        stem, dot, last = ref.rpartition(".")
        ref = (stem.replace(".", "/") + "." + last if dot and f".{last}" in _KNOWN_SUFFIXES
               else ref.replace(".", "/"))
    path = (base / ref).resolve()
    if path.suffix in _KNOWN_SUFFIXES:
        candidates = [path]
    else:
        candidates = [path.with_name(path.name + ext) for ext in _EXTENSIONS[use.case]]
    for candidate in candidates:
        if candidate.is_file():
            return candidate
    for candidate in candidates:
        if (found := _differing_in_case(candidate)) is not None:
            return found
    how = f" as {use.case}" if use.case else ""
    tried = " or ".join(str(c) for c in candidates)
    suffixes = {c.suffix for c in candidates} | ({path.suffix} - {""})
    present = ([p.stem for p in path.parent.iterdir() if p.suffix in suffixes]
               if path.parent.is_dir() else [])
    close = difflib.get_close_matches(Path(ref).stem, present, n=1)
    hint = f"; did you mean {close[0]}?" if close else ""
    raise GoalSyntaxError.at(use.pos, f"use {use.ref}{how}: no such file ({tried}){hint}")


def _differing_in_case(path: Path) -> Path | None:
    """The one file beside a missing ``path`` whose name differs from it in case only: GOAL
    programs are written on Windows and macOS, whose file systems find ``Zerghatchery.act2g``
    as ``ZergHatchery.act2g``; None when ``path`` is there, or none or several differ so."""
    try:
        if path.is_file() or not path.parent.is_dir():
            return None
        same = [p for p in path.parent.iterdir()
                if p.name.casefold() == path.name.casefold() and p.is_file()]
    except OSError:  # a name too long for the file system: read_program_file says so
        return None
    return same[0] if len(same) == 1 else None


def _wildcard_matches(use: ast.UseClause, base: Path) -> list[Path]:
    """The files a quoted reference with ``*`` names (``use 'util/*.pl' as knowledge.``),
    sorted; a wildcard that matches nothing is an error at the use clause."""
    if not use.quoted or "*" not in use.ref:
        return []
    matches = sorted(Path(p).resolve() for p in glob.glob(str(base / use.ref))
                     if Path(p).is_file())
    if not matches:
        raise GoalSyntaxError.at(use.pos, f"use {use.ref}: no file matches")
    return matches


def parse_module_file(path: str | Path, *, plain_beliefs: bool = False) -> ModuleFile:
    """Parse a GOAL 6+ module file (`.mod2g`)."""
    return _parsed_file(path, "module_file", plain_beliefs=plain_beliefs)


def parse_action_file(path: str | Path) -> ActionFile:
    """Parse a GOAL 6+ action specification file (`.act2g`)."""
    return _parsed_file(path, "action_file")


def parse_clause_file(path: str | Path, *, split_facts: bool = True
                      ) -> tuple[ast.PrologText, ...]:
    """The clauses of a Prolog file; with ``split_facts`` False each clause stays whole
    (a goals file's ``on(a,b), on(b,c).`` is one goal)."""
    return _parsed_file(path, "prolog_file", split_facts=split_facts)


def _parsed_file(path: str | Path, start: str, **options: bool) -> Any:
    """What ``build`` makes of the file from rule ``start``: a copy of this process's earlier
    parse of the same text (goalagent.parser.reparse)."""
    text = read_program_file(path)
    key = (start, str(path), tuple(sorted(options.items())))
    return parsed_once(text, key, lambda: build(text, str(path), start, **options)[0])


def load_agents(mas: ast.MasProgram) -> dict[str, ast.AgentProgram]:
    """Every agent of a system by name: its agent files' and its agent definitions'."""
    base = Path(mas.file).parent
    programs = {}
    for agentfile in mas.agentfiles:
        path = base / agentfile.path
        path = _differing_in_case(path) or path
        try:  # only a regular file of bounded size; why not is said at the agentfiles entry
            text = read_program_file(path)
        except GoalSyntaxError as err:
            reason = (f"no such file next to {Path(mas.file).name}"
                      if err.message == "no such file" else err.message)
            raise GoalSyntaxError.at(agentfile.pos, f"agent file {agentfile.path!r}: "
                                     f"{reason}") from None
        if path.suffix != ".goal":  # parsing it would quote its text in the error
            raise GoalSyntaxError.at(agentfile.pos, f"agent file {agentfile.path!r}: not a "
                                     "GOAL agent file (its name ends in .goal)")
        programs[agentfile.name] = parse_agent(text, str(path))
    for definition in mas.definitions:
        programs[definition.name] = load_definition(definition, mas.file)
    return programs


def load_definition(definition: ast.AgentDefinition, mas_file: str) -> ast.AgentProgram:
    """The program of a GOAL 6+ agent definition: its modules and all they use."""
    loader = _AgentLoader(definition)
    base = Path(mas_file).parent
    for use in definition.uses:
        if use.case == "shutdown":
            raise GoalSyntaxError.at(use.pos, "shutdown modules are not supported by "
                                     "goalagent yet")
        role = _ROLES[str(use.case)]
        if any(m.name == role for m in loader.roles):
            raise GoalSyntaxError.at(use.pos, f"agent {definition.name} has two {role} modules")
        loader.roles.append(loader.role_module(use, base, role))
    if definition.percept_rules:
        loader.add_percept_rules(definition.percept_rules)
    return loader.program(mas_file)


def load_module_as_agent(path: str | Path) -> ast.AgentProgram:
    """A module file on its own as an agent whose main module it is (``goalagent check``
    of a `.mod2g`: its uses resolved, its actions checked against what it uses)."""
    path = Path(path)
    use = ast.UseClause(path.name, "main", ast.Pos(str(path), 1, 1), quoted=True)
    definition = ast.AgentDefinition(path.stem, use.pos, (use,))
    try:
        return load_definition(definition, str(path))
    except GoalSyntaxError as err:
        if "unknown mental literal" not in err.message:
            raise
        # the newest dialect writes belief queries bare: read it so, as `use m for decisions`
        newest = ast.AgentDefinition(path.stem, use.pos, (replace(use, case="decisions"),))
        return load_definition(newest, str(path))


class _AgentLoader:
    """Gathers what an agent definition's module files use, each file once."""

    def __init__(self, definition: ast.AgentDefinition) -> None:
        self.definition = definition
        self.newest = any(use.case in ("decisions", "updates") for use in definition.uses)
        self.roles: list[ast.Module] = []
        self.users: dict[Path, ast.Module] = {}
        self.macros: list[ast.Macro] = []
        self.top: dict[str, list] = {"knowledge": [], "beliefs": [], "goals": [],
                                     "actionspecs": []}
        self._done: set[tuple[Path, str]] = set()

    def role_module(self, use: ast.UseClause, base: Path, role: str) -> ast.Module:
        """The module file ``use`` names, as the agent's ``role`` module."""
        path = resolve_reference(replace(use, case="module"), base)
        module_file = self._module_file(path)
        module = module_file.module
        return replace(module, name=role, kind=role)  # type: ignore[arg-type]

    def _module_file(self, path: Path) -> ModuleFile:
        module_file = parse_module_file(path, plain_beliefs=self.newest)
        self.macros.extend(module_file.macros)
        self._uses(module_file.uses, path.parent)
        return module_file

    def _uses(self, uses: tuple[ast.UseClause, ...], base: Path) -> None:
        for use in uses:
            if use.case not in (None, "knowledge", "beliefs", "goals", "actionspec", "module"):
                raise GoalSyntaxError.at(use.pos, f"use {use.ref} as {use.case}: a module "
                                         "file uses files as knowledge, beliefs, goals, "
                                         "actionspec or module")
            for path in _wildcard_matches(use, base) or [resolve_reference(use, base)]:
                self._use(use, path)

    def _use(self, use: ast.UseClause, path: Path) -> None:
        """Reads the file ``path`` that ``use`` names (once per file and use)."""
        case = use.case or {".pl": "knowledge", ".act2g": "actionspec"}.get(
            path.suffix, "module")
        if (path, case) in self._done:
            return
        self._done.add((path, case))
        if case == "module":
            self.users[path] = self._module_file(path).module
        elif case == "actionspec":
            action_file = parse_action_file(path)
            self._uses(action_file.uses, path.parent)
            self.top["actionspecs"].extend(action_file.specs)
        elif case == "goals":
            self.top["goals"].extend(parse_clause_file(path, split_facts=False))
        else:
            self.top[case].extend(parse_clause_file(path))

    def add_percept_rules(self, rules: tuple[ast.PerceptRule, ...]) -> None:
        """The newest dialect's percept rules as forall rules first in the event module."""
        generated = tuple(rule for percept_rule in rules for rule in _percept_rules(percept_rule))
        for index, module in enumerate(self.roles):
            if module.kind == "event":
                self.roles[index] = replace(module, rules=generated + module.rules)
                return
        self.roles.append(ast.Module("event", "event", rules[0].pos, rules=generated))

    def program(self, file: str) -> ast.AgentProgram:
        modules = [*self.roles, *self.users.values()]
        if self.newest:
            self.top["actionspecs"].extend(_environment_actions(modules, self.top["actionspecs"]))
        program = finish_program(self.definition.name, file, modules, self.macros, self.top)
        return replace(program, messages_for_one_cycle=True)


def _text(text: str, pos: ast.Pos) -> ast.PrologText:
    """Prolog text made by goalagent, read like the program's own."""
    return ast.PrologText(text, pos, tuple(get_engine().check_query(text)))


def _percept_rules(rule: ast.PerceptRule) -> list[ast.Rule]:
    """``add``: percepts of p/N become beliefs; ``replace``: beliefs of p/N not perceived
    are deleted too; ``update``: as replace, but only in cycles with p/N percepts."""
    pos = rule.pos
    args = ", ".join(f"A{i}" for i in range(1, rule.arity + 1))
    atom = f"{rule.name}({args})" if rule.arity else rule.name
    anything = (f"{rule.name}({', '.join('_' * rule.arity)})" if rule.arity
                else rule.name)

    def literal(op: str, text: str) -> ast.MentalLiteral:
        return ast.MentalLiteral(op, _text(text, pos), pos)  # type: ignore[arg-type]

    def update(name: str) -> tuple[ast.ActionCall]:
        return (ast.ActionCall(name, (_text(atom, pos),), pos),)

    insert = ast.Rule("forall", (literal("percept", atom),
                                 ast.NotLiteral((literal("bel", atom),), pos)), pos,
                      actions=update("insert"))
    if rule.how == "add":
        return [insert]
    removal: tuple[ast.Literal, ...] = (literal("bel", atom),
                                        ast.NotLiteral((literal("percept", atom),), pos))
    if rule.how == "update":
        removal = (literal("percept", anything), *removal)
    return [ast.Rule("forall", removal, pos, actions=update("delete")), insert]


def _environment_actions(modules: list[ast.Module], specs: list[ast.ActionSpec]
                         ) -> list[ast.ActionSpec]:
    """Specifications (always enabled, no effect) for the actions no file specifies: the
    newest dialect sends them to the environment as they are."""
    known = {(spec.name, spec.arity) for spec in specs}
    known |= {(module.declared or module.name, module.arity) for module in modules}
    made: list[ast.ActionSpec] = []
    for module in modules:
        for rule in ast.iter_rules(module.rules):
            for action in rule.actions:
                if (not isinstance(action, ast.ActionCall) or action.builtin
                        or (action.name, action.arity) in known):
                    continue
                known.add((action.name, action.arity))
                params = tuple(_text(f"A{i}", action.pos) for i in range(1, action.arity + 1))
                true = _text("true", action.pos)
                made.append(ast.ActionSpec(action.name, params, true, true, action.pos))
    return made
