"""`.goal` agent programs (GOAL's single-file format): parse, gather what is global to the
agent, and warn about singleton variables as GOAL does."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator
from dataclasses import replace
from functools import partial
from pathlib import Path

from goalagent import ast
from goalagent.kb.engine import get_engine
from goalagent.parser.ast_builder import AstBuilder, build
from goalagent.parser.builder_base import ParsedSection
from goalagent.parser.conditions import condition_texts
from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.reparse import parsed_once
from goalagent.parser.source import read_program_file
from goalagent.parser.variables import variable_occurrences


def parse_agent(text: str, file: str = "<string>") -> ast.AgentProgram:
    """Parse the text of a `.goal` agent program (a text parsed before in this process, with
    its imports as they were: a copy of that parse, see goalagent.parser.reparse)."""
    return parsed_once(text, ("agent", file), partial(_parse_agent, text, file))


def _parse_agent(text: str, file: str) -> ast.AgentProgram:
    """The parse itself: lark's tree of the text, its Prolog read by SWI-Prolog."""
    try:
        (name, items), builder = build(text, file, "agent")  # type: ignore[misc]
    except GoalSyntaxError as err:
        if err.message.startswith(("unexpected 'use'", "unexpected 'define'")):
            raise GoalSyntaxError(err.file, err.line, err.col, f"{err.message} -- `use` and "
                                  "`define` belong to GOAL 6's multi-file format: module files "
                                  "(.mod2g) run through the .mas2g that uses them") from None
        raise
    return _program_from_items(name, items, file, builder)


def parse_agent_file(path: str | Path) -> ast.AgentProgram:
    """Parse a `.goal` file (any extension but `.mas2g`)."""
    return parse_agent(read_program_file(path), str(path))


def _program_from_items(name: str | None, items: list, file: str,
                        builder: AstBuilder) -> ast.AgentProgram:
    """The program of a file's top-level items: its modules (a program section outside any
    module is the main module) and, gathered from all of them, what is global to the agent."""
    modules: list[ast.Module] = []
    top: dict[str, list] = {"knowledge": [], "beliefs": [], "goals": [], "actionspecs": []}
    top_program: ParsedSection | None = None
    for item in items:
        if isinstance(item, ast.Module):
            if item.kind != "user" and any(m.name == item.name for m in modules):
                raise GoalSyntaxError.at(item.pos, f"there is already a {item.name} module")
            modules.append(item)
        elif isinstance(item, ParsedSection):
            if item.kind == "modules":
                for module in item.items:
                    if module.kind != "user" and any(m.name == module.name for m in modules):
                        raise GoalSyntaxError.at(item.pos, f"the imported {module.name} "
                                                 "module: there is already one")
                    modules.append(module)
            elif item.kind == "program":
                top_program = item
            elif item.kind == "perceptrules":
                builder.percept_rules.extend(item.items)
            else:
                top[item.kind].extend(item.items)
    if top_program is not None:
        if any(m.kind == "main" for m in modules):
            raise GoalSyntaxError.at(top_program.pos,
                                     "a program section outside modules and a main module")
        modules.append(ast.Module("main", "main", top_program.pos, rules=top_program.items,
                                  order=top_program.options.get("order")))
    modules.extend(builder.nested_modules)
    if builder.percept_rules:
        modules = _with_percept_rules(modules, tuple(builder.percept_rules))
    program = finish_program(name or Path(file).stem, file, modules, builder.macro_list, top)
    if builder.warnings:
        program = replace(program, warnings=(*builder.warnings, *program.warnings))
    return program


def _with_percept_rules(modules: list[ast.Module],
                        rules: tuple[ast.Rule, ...]) -> list[ast.Module]:
    """GOAL 3's percept rules run first in the event module (one is made if needed)."""
    for index, module in enumerate(modules):
        if module.kind == "event":
            modules[index] = replace(module, rules=rules + module.rules)
            return modules
    return [*modules, ast.Module("event", "event", rules[0].pos, rules=rules)]


def finish_program(name: str, file: str, modules: list[ast.Module], macros: list[ast.Macro],
                   top: dict[str, list]) -> ast.AgentProgram:
    """The agent program of ``modules`` (whatever format they were read from) with what is
    global to the agent gathered from them and ``top`` (knowledge, beliefs, goals and
    actionspecs written outside modules), ``@env`` overrides marked and singleton variables
    warned about. A user module's goals stay its own: adopted when it is entered, its
    parameters instantiating them (GOAL's semantics)."""
    everything = [top, *({"knowledge": list(m.knowledge), "beliefs": list(m.beliefs),
                          "goals": list(m.goals) if m.kind != "user" else [],
                          "actionspecs": list(m.actionspecs)}
                         for m in modules)]
    gathered = {key: tuple(x for part in everything for x in part[key]) for key in top}
    overriding = {(spec.name, spec.arity) for spec in gathered["actionspecs"]
                  if spec.name in ast.BUILTIN_ACTIONS}
    if overriding:
        modules = [replace(m, rules=_mark_overrides(m.rules, overriding)) for m in modules]
    selecting = {(m.name, m.arity) for m in modules if m.kind == "user" and m.focus == "select"}
    if selecting:
        modules = [replace(m, rules=_in_one_goal(m.rules, selecting)) for m in modules]
    program = ast.AgentProgram(
        name=name,
        file=file,
        modules=tuple(modules),
        macros=tuple(macros),
        knowledge=gathered["knowledge"],
        beliefs=gathered["beliefs"],
        goals=gathered["goals"],
        actionspecs=gathered["actionspecs"],
    )
    return _with_singleton_warnings(program)


def _mark_overrides(rules: tuple[ast.Rule, ...],
                    overriding: set[tuple[str, int]]) -> tuple[ast.Rule, ...]:
    """Calls of built-in names that an ``@env`` actionspec declares go to that actionspec."""
    marked = []
    for rule in rules:
        actions = tuple(
            replace(a, overrides_builtin=True)
            if isinstance(a, ast.ActionCall) and (a.name, a.arity) in overriding else a
            for a in rule.actions
        )
        inner = _mark_overrides(rule.rules, overriding) if rule.rules else rule.rules
        marked.append(replace(rule, actions=actions, rules=inner))
    return tuple(marked)


def _in_one_goal(rules: tuple[ast.Rule, ...],
                 selecting: set[tuple[str, int]]) -> tuple[ast.Rule, ...]:
    """A rule that enters a ``focus=select`` module selects one goal: its goal literals
    (goal, a-goal, goal-a) must hold in that one goal together, as in GOAL (its runtime
    test testselect.goal). The rule's condition gets the literal ``goal((φ1, ..., φn))``
    after its last goal literal."""
    result = []
    for rule in rules:
        inner = _in_one_goal(rule.rules, selecting) if rule.rules else rule.rules
        enters = any(isinstance(a, ast.ActionCall) and (a.name, a.arity) in selecting
                     for a in rule.actions)
        positions = [i for i, literal in enumerate(rule.condition)
                     if isinstance(literal, ast.MentalLiteral)
                     and literal.op in ("goal", "a-goal", "goal-a")]
        condition = rule.condition
        if enters and len(positions) > 1:
            last = rule.condition[positions[-1]]
            texts = ", ".join(f"({rule.condition[i].query.text}\n)"  # type: ignore[union-attr]
                              for i in positions)
            text = f"({texts})"
            joint = ast.MentalLiteral("goal", ast.PrologText(
                text, last.pos, tuple(get_engine().check_query(text))), last.pos)
            condition = (*condition[:positions[-1] + 1], joint, *condition[positions[-1] + 1:])
        result.append(replace(rule, condition=condition, rules=inner))
    return tuple(result)


def _rule_texts(rule: ast.Rule) -> Iterator[ast.PrologText]:
    """Every Prolog text of a rule: condition, actions, nested rules."""
    yield from condition_texts(rule.condition)
    for action in rule.actions:
        if isinstance(action, ast.SendAction):
            yield action.receiver
            yield action.content
        else:
            yield from action.args
    for inner in rule.rules or ():
        yield from _rule_texts(inner)


def _with_singleton_warnings(program: ast.AgentProgram) -> ast.AgentProgram:
    """Singleton variables in rules, as GOAL reports them (warnings, not errors)."""
    warnings = []
    for module in program.modules:
        for rule in module.rules:
            counts: Counter[str] = Counter()
            for text in _rule_texts(rule):
                counts.update(variable_occurrences(text.text))
            if rule.list_var:  # listall uses its list variable and what it collects
                counts[rule.list_var] += 1
                for text in condition_texts(rule.condition):
                    counts.update(variable_occurrences(text.text))
            for param in module.params:  # module parameters are bound by the caller
                for var in variable_occurrences(param.text):
                    if counts[var]:
                        counts[var] += 1
            for var, count in counts.items():
                if count == 1 and not var.startswith("_") and not ast.is_macro_local(var):
                    warnings.append(f"{rule.pos}: warning: singleton variable {var} in rule")
    if not warnings:
        return program
    return replace(program, warnings=tuple(warnings))
