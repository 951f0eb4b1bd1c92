"""Program checks made when an agent is loaded (and by ``goalagent check``): every action a
rule performs is built in (with its arity), declared in an actionspec, or a module."""

from __future__ import annotations

import difflib
from collections.abc import Iterator

from goalagent import ast
from goalagent.agent.validator import structure_errors
from goalagent.parser import GoalSyntaxError, variable_occurrences

# Built-in actions and their number of arguments (None: one formula, commas allowed).
_BUILTIN_ARITY = {"insert": None, "delete": None, "adopt": None, "drop": None, "print": 1,
                  "log": 1, "exit-module": 0, "sleep": 1, "starttimer": 3,
                  "canceltimer": None, "subscribe": None, "unsubscribe": None}
_UPDATES = frozenset({"insert", "delete", "adopt", "drop"})


def validate_program(program: ast.AgentProgram) -> None:
    """What an agent cannot run without (checked when it is loaded): ground goals, and
    every action built in (with its arity), specified or a user module; raises
    ``GoalSyntaxError`` at the first problem."""
    _check_ground_goals(program)
    for error in _action_errors(program):
        raise error


def program_errors(program: ast.AgentProgram) -> list[GoalSyntaxError]:
    """Everything GOAL's validator finds wrong in a program (``goalagent check``), in
    source order: what :func:`validate_program` checks and the rules of ``validator``."""
    errors: list[GoalSyntaxError] = []
    try:
        _check_ground_goals(program)
    except GoalSyntaxError as err:
        errors.append(err)
    errors.extend(_action_errors(program))
    errors.extend(structure_errors(program))
    return sorted(errors, key=lambda err: (err.file, err.line, err.col))


def _action_errors(program: ast.AgentProgram) -> Iterator[GoalSyntaxError]:
    """Every action in a rule must be built in, specified or a user module (with its arity);
    an error for each one that is not."""
    specs = {(spec.name, spec.arity) for spec in program.actionspecs}
    modules = {(m.name, m.arity) for m in program.modules}
    for module in program.modules:
        for rule in ast.iter_rules(module.rules):
            yield from _condition_errors(rule.condition)
            for action in rule.actions:
                if isinstance(action, ast.SendAction):
                    continue
                key = (action.name, action.arity)
                if action.builtin:
                    expected = _BUILTIN_ARITY[action.name]
                    if (expected is None and action.arity == 0) or (
                        expected is not None and action.arity != expected
                    ):
                        yield GoalSyntaxError.at(
                            action.pos, f"{action.name} takes "
                            f"{'an argument' if expected is None else expected} argument(s), "
                            f"not {action.arity}")
                elif key not in specs and key not in modules:
                    known = sorted(f"{n}/{a}" for n, a in (*specs, *modules))
                    names = sorted({n for n, _ in (*specs, *modules)} | ast.BUILTIN_ACTIONS)
                    close = difflib.get_close_matches(action.name, names, n=1)
                    hint = f"did you mean {close[0]}? " if close else ""
                    yield GoalSyntaxError.at(
                        action.pos,
                        f"unknown action {action.name}/{action.arity}: not built in, not in an "
                        f"actionspec and not a module ({hint}known: "
                        f"{', '.join(known) or 'none'})",
                    )


def _check_ground_goals(program: ast.AgentProgram) -> None:
    """Goals in a ``goals`` section must be ground, but for a user module's parameters
    (bound when the module is entered): located here, not when adopted."""
    sections = [(goal, ()) for goal in program.goals]
    sections += [(goal, module.params) for module in program.modules if module.kind == "user"
                 for goal in module.goals]
    for goal, params in sections:
        bound = {var for param in params for var in variable_occurrences(param.text)}
        names = [name for name in dict.fromkeys(variable_occurrences(goal.text))
                 if name not in bound]
        if names:
            where = ("a goals section holds ground goals" if not params else
                     "only the module's parameters may occur in its goals")
            raise GoalSyntaxError.at(
                goal.pos, f"goal {goal.text.strip()} is not ground (variable(s) "
                f"{', '.join(names)}): {where}; adopt a goal with variables from a rule "
                "whose condition binds them")


def _condition_errors(condition: ast.Condition) -> Iterator[GoalSyntaxError]:
    """``done(Action)`` belongs to tests, not to a rule's condition."""
    for literal in condition:
        if isinstance(literal, ast.NotLiteral):
            yield from _condition_errors(literal.condition)
        elif literal.op == "done":
            yield GoalSyntaxError.at(literal.pos, "done(...) is a test condition (.test2g); "
                                     "a rule's condition cannot use it")


def update_formulas(program: ast.AgentProgram) -> list[ast.PrologText]:
    """Every formula the agent may insert or delete (so its predicates are dynamic)."""
    formulas = list(program.goals) + [spec.post for spec in program.actionspecs]
    formulas += [goal for module in program.modules for goal in module.goals]
    for module in program.modules:
        for rule in ast.iter_rules(module.rules):
            for action in rule.actions:
                if isinstance(action, ast.ActionCall) and action.builtin and (
                    action.name in _UPDATES
                ):
                    formulas.extend(action.args)
    return formulas
