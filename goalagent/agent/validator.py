"""GOAL's validator rules about a program's structure and variables, beyond the actions it
calls (``checks``): what GOAL's own validator tests (``AgentValidatorErrorTest``,
``AgentValidatorWarningTest``) say is an error or a warning. Each rule returns every finding
with its place, so ``goalagent check`` reports them all at once.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator

from goalagent import ast
from goalagent.kb.engine import KBError, get_engine
from goalagent.kb.terms import Struct
from goalagent.parser import GoalSyntaxError, variable_occurrences
from goalagent.parser.conditions import condition_texts

_BINDING_ACTIONS = frozenset({"print", "log", "insert", "adopt", "send", "sendonce"})
_INVALID_RECEIVERS = frozenset({"some", "someother", "this"})


def structure_errors(program: ast.AgentProgram) -> list[GoalSyntaxError]:
    """GOAL's validator errors about modules, macros, actionspecs, goals and variables."""
    errors: list[GoalSyntaxError] = []
    for check in (_main_or_event, _program_sections, _goal_clauses, _duplicate_macros,
                  _macro_parameters, _duplicate_actions, _actionspec_parameters,
                  _module_parameters, _unbound_action_variables):
        errors.extend(check(program))
    return errors


def structure_warnings(program: ast.AgentProgram) -> list[str]:
    """GOAL's validator warnings: an empty program section, actions after exit-module."""
    warnings = []
    for module in program.modules:
        if module.kind != "init" and module.has_program and not module.rules:
            warnings.append(f"{module.pos}: warning: module {module.name} has an empty "
                            "program section")
        for rule in ast.iter_rules(module.rules):
            names = [action.name for action in rule.actions]
            if "exit-module" in names[:-1]:
                after = rule.actions[names.index("exit-module") + 1]
                warnings.append(f"{after.pos}: warning: {after.name} is never done: "
                                "exit-module before it leaves the module")
    return warnings


def _main_or_event(program: ast.AgentProgram) -> Iterator[GoalSyntaxError]:
    """An agent needs a main or an event module (a GOAL 5 module file is part of one)."""
    if program.file.endswith(".mod2g"):
        return
    if not any(module.kind in ("main", "event") for module in program.modules):
        first = program.modules[0].pos if program.modules else ast.Pos(program.file, 1, 1)
        yield GoalSyntaxError.at(first, "the program has neither a main nor an event module: "
                                 "nothing would run after init")


def _program_sections(program: ast.AgentProgram) -> Iterator[GoalSyntaxError]:
    for module in program.modules:
        if module.kind != "init" and not module.has_program:
            yield GoalSyntaxError.at(module.pos, f"module {module.name} has no program "
                                     "section")


def _goal_clauses(program: ast.AgentProgram) -> Iterator[GoalSyntaxError]:
    """A goal is a conjunction of facts, never a rule ``h :- b``."""
    goals = [*program.goals, *(g for m in program.modules if m.kind == "user" for g in m.goals)]
    for goal in goals:
        try:
            term = get_engine().parse_term(goal.text)
        except KBError:
            continue
        if isinstance(term, Struct) and term.name == ":-":
            yield GoalSyntaxError.at(goal.pos, f"goal {goal.text.strip()} is a rule; a goals "
                                     "section holds goals (conjunctions of facts)")


def _duplicate_macros(program: ast.AgentProgram) -> Iterator[GoalSyntaxError]:
    """A macro is defined once in its module (the module written last before it)."""
    starts = sorted((m.pos.file, m.pos.offset) for m in program.modules)
    seen: set[tuple] = set()
    for macro in program.macros:
        owner = max((start for start in starts if start[0] == macro.pos.file
                     and start[1] <= macro.pos.offset), default=None)
        key = (macro.pos.file, owner, macro.name, len(macro.params))
        if key in seen:
            yield GoalSyntaxError.at(macro.pos, f"macro {macro.name}/{len(macro.params)} is "
                                     "defined twice")
        seen.add(key)


def _macro_parameters(program: ast.AgentProgram) -> Iterator[GoalSyntaxError]:
    for macro in program.macros:
        used = {var for text in condition_texts(macro.condition)
                for var in variable_occurrences(text.text)}
        missing = [param for param in macro.params if param not in used]
        if missing:
            yield GoalSyntaxError.at(macro.pos, f"macro {macro.name}: parameter(s) "
                                     f"{', '.join(missing)} do not occur in its definition")


def _duplicate_actions(program: ast.AgentProgram) -> Iterator[GoalSyntaxError]:
    """One actionspec per name/arity in a module (GOAL 4/5 modules may each specify their
    own), and none named as a module."""
    modules = {(m.name, m.arity) for m in program.modules if m.kind == "user"}
    written = {id(spec) for m in program.modules for spec in m.actionspecs}
    scopes = [m.actionspecs for m in program.modules]
    scopes.append(tuple(spec for spec in program.actionspecs if id(spec) not in written))
    for specs in scopes:
        seen: set[tuple[str, int]] = set()
        for spec in specs:
            key = (spec.name, spec.arity)
            if key in seen or key in modules:
                what = "a module" if key in modules else "another actionspec"
                yield GoalSyntaxError.at(spec.pos, f"action {spec.name}/{spec.arity} is "
                                         f"already defined by {what}")
            seen.add(key)


def _actionspec_parameters(program: ast.AgentProgram) -> Iterator[GoalSyntaxError]:
    """Distinct parameters; a postcondition's variables bound by them, the precondition or
    the parameters of the module the actionspec is written in."""
    given = {id(spec): {var for param in module.params for var in variable_occurrences(param.text)}
             for module in program.modules for spec in module.actionspecs}
    for spec in program.actionspecs:
        params = [var for param in spec.params for var in variable_occurrences(param.text)]
        twice = [var for var, count in Counter(params).items() if count > 1]
        if twice:
            yield GoalSyntaxError.at(spec.pos, f"action {spec.name}: parameter "
                                     f"{twice[0]} occurs twice")
        bound = set(params) | set(variable_occurrences(spec.pre.text)) | given.get(id(spec), set())
        unbound = [var for var in dict.fromkeys(variable_occurrences(spec.post.text))
                   if var not in bound and not var.startswith("_")]
        if unbound:
            yield GoalSyntaxError.at(spec.post.pos, f"the postcondition of {spec.name} uses "
                                     f"{', '.join(unbound)}, bound by neither its parameters "
                                     "nor its precondition")


def _module_parameters(program: ast.AgentProgram) -> Iterator[GoalSyntaxError]:
    for module in program.modules:
        for param in module.params:
            if not _is_variable(param.text):
                yield GoalSyntaxError.at(param.pos, f"module {module.name}: parameter "
                                         f"{param.text} is not a variable")


def _unbound_action_variables(program: ast.AgentProgram) -> Iterator[GoalSyntaxError]:
    """Variables an action needs that nothing binds, and anonymous receivers/list
    variables (GOAL's RULE_VARIABLE_NOT_BOUND, SEND_INVALID_SELECTOR, anonymous ones)."""
    for module in program.modules:
        bound = {var for param in module.params for var in variable_occurrences(param.text)}
        yield from _rules_unbound(module.rules, bound)


def _rules_unbound(rules: tuple[ast.Rule, ...], outer: set[str]) -> Iterator[GoalSyntaxError]:
    for rule in rules:
        bound = outer | {var for text in condition_texts(rule.condition)
                         for var in variable_occurrences(text.text)}
        if rule.list_var is not None:
            if rule.list_var.startswith("_"):
                yield GoalSyntaxError.at(rule.pos, "listall needs a named list variable, "
                                         f"not {rule.list_var}")
            bound.add(rule.list_var)
        for action in rule.actions:
            yield from _action_unbound(action, bound)
            if isinstance(action, ast.ActionCall) and not action.builtin:
                # a user action's precondition may bind its arguments for what follows
                bound |= {var for arg in action.args for var in variable_occurrences(arg.text)}
        if rule.rules:
            yield from _rules_unbound(rule.rules, bound)


def _action_unbound(action: ast.Action, bound: set[str]) -> Iterator[GoalSyntaxError]:
    if isinstance(action, ast.SendAction):
        receiver = action.receiver.text.strip("() ")
        if receiver in _INVALID_RECEIVERS or receiver.startswith("_"):
            yield GoalSyntaxError.at(action.pos, f"{receiver}.{action.name}: a message goes "
                                     "to an agent, a bound variable, all or allother")
        texts = [action.receiver, action.content]
    elif action.builtin and action.name in _BINDING_ACTIONS:
        texts = list(action.args)
    else:
        return
    free = [var for text in texts for var in variable_occurrences(text.text)
            if var not in bound and not var.startswith("_") and not ast.is_macro_local(var)]
    if free:
        yield GoalSyntaxError.at(action.pos, f"{action.name}: variable(s) "
                                 f"{', '.join(dict.fromkeys(free))} bound by nothing in the "
                                 "rule's condition")


def _is_variable(text: str) -> bool:
    names = list(variable_occurrences(text))
    return len(names) == 1 and names[0] == text.strip()
