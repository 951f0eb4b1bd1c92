"""Module calls: a rule's action that names a module runs that module's rules, with the
module's parameters bound to the call's arguments, its own goal base as its ``focus``
option says, and -- unless its ``exit`` option is ``always`` -- stays the agent's focus in
the next cycles until it exits."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from goalagent import ast
from goalagent.agent.events import module_event
from goalagent.agent.reports import describe
from goalagent.events import EventKind
from goalagent.kb.interpreter_requests import Firing
from goalagent.kb.mentalstate import MentalState
from goalagent.kb.terms import Struct, Term

if TYPE_CHECKING:
    from goalagent.agent.cycle import Agent
    from goalagent.agent.rules import RuleApplication

Bindings = dict[str, Term]


@dataclass
class Focus:
    """A user module the agent stays in across cycles (exit other than always)."""

    module: ast.Module
    bindings: Bindings
    own_goal_base: bool


def call_module(agent: Agent, rules: RuleApplication, firing: Firing, index: int,
                module: ast.Module, args: list[Term], entries: int, position: int) -> bool:
    """Runs ``module`` called by action ``index`` of ``firing`` with ``args``; False when
    its parameters do not match them. ``entries`` and ``position``: where the call happens
    in the running interpreter call's journal (its report spans are split there)."""
    bindings: Bindings | None = {}
    for param, arg in zip(module.params, args, strict=True):
        bindings = agent.ms.unify(param, arg, bindings)
        if bindings is None:
            return False
    description = describe(firing.rule.rule.actions[index], firing.bindings)
    if agent.listeners:
        agent.tell(module_event(agent.name, EventKind.MODULE_ENTERED, module, description))
    own_goal_base = _enter_goal_focus(agent.ms, module, firing.rule.rule.condition,
                                      firing.bindings)
    for goal in module.goals:  # adopted on entry, the parameters instantiating them
        agent.ms.adopt(goal, bindings)
    exit_option = (module.exit or "always") if module.kind == "user" else "always"
    rules.split_at(entries, position)
    outcome = rules.run_modules([(module, bindings)])
    if exit_option == "always" or outcome.exited:
        if own_goal_base:
            agent.ms.pop_goal_base()
    else:
        agent.focus.append(Focus(module, bindings, own_goal_base))
    return True


def leave_focus(agent: Agent) -> None:
    """The module in focus exits: the agent returns to its main module."""
    focus = agent.focus.pop()
    if focus.own_goal_base:
        agent.ms.pop_goal_base()
    if agent.listeners:
        agent.tell(module_event(agent.name, EventKind.MODULE_LEFT, focus.module,
                                focus.module.declared or focus.module.name))


def _enter_goal_focus(ms: MentalState, module: ast.Module, condition: ast.Condition,
                      bindings: Bindings) -> bool:
    """Give the module its own goal base as its ``focus`` option says: ``new`` an empty
    one; ``filter`` the goals the calling rule's condition names (its goal, a-goal and
    goal-a literals, instantiated); ``select`` the current goal that contains them."""
    focus = module.focus or "none"
    if focus == "none":
        return False
    named = [_conjuncts(ms.instantiate(literal.query, bindings))
             for literal in condition
             if isinstance(literal, ast.MentalLiteral) and literal.query is not None
             and literal.op in ("goal", "a-goal", "goal-a")]
    if focus == "new":
        ms.push_goal_base([])
    elif focus == "filter":
        ms.push_goal_base(named)
    else:
        wanted = [fact for facts in named for fact in facts]
        ms.push_goal_base([goal for goal in ms.goals()
                           if all(fact in goal for fact in wanted)][:1])
    return True


def _conjuncts(term: Term) -> list[Term]:
    """The facts of a conjunction ``(a, b, c)``."""
    if isinstance(term, Struct) and term.name == "," and term.arity == 2:
        return _conjuncts(term.args[0]) + _conjuncts(term.args[1])
    return [term]
