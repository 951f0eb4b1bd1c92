"""Rule application: an agent's modules run on the one rule interpreter
(``goalagent.kb.interpreter``), whose requests are answered here -- environment actions,
print/log, messages, module calls, the agent's random rule order, warnings and events --
and whose journals become the cycle report's spans."""

from __future__ import annotations

import sys
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

from goalagent import ast
from goalagent.agent import actions, messages, modules, timers
from goalagent.agent.errors import AgentError
from goalagent.agent.events import interpreter_event
from goalagent.agent.problems import warning_text
from goalagent.agent.reports import RunRecord, Span
from goalagent.kb.interpreter import CompiledProgram, RunOutcome
from goalagent.kb.interpreter_requests import Firing, Problem, Step
from goalagent.kb.mentalstate import PlanPredicate
from goalagent.kb.terms import Term

if TYPE_CHECKING:
    from goalagent.agent.cycle import Agent

FRAMES_PER_LEVEL = 60
"""Python frames one nested module call uses (Python's recursion limit is raised by as many
for each level, so a term deep inside the last level meets the same limit as at the top)."""


class _CyclePlans(dict):
    """The plans of a cycle without a module in focus, by (first cycle, has listeners):
    the init (first cycle), event and main modules that exist; None when none does.
    Planned on first use."""

    def __init__(self, agent: Agent, code: CompiledProgram) -> None:
        super().__init__()
        self._agent = agent
        self._code = code

    def __missing__(self, key: tuple[bool, bool]) -> Term | PlanPredicate | None:
        first, listen = key
        program = self._agent.program
        names = ("init", "event", "main") if first else ("event", "main")
        modules = [(module, {}) for module in map(program.module, names) if module is not None]
        plan = self._code.plan(modules, environment=self._agent.io is not None,
                               listen=listen) if modules else None
        self[key] = plan
        return plan


class RuleApplication:
    """Runs one agent's modules on the interpreter and answers what it asks (this object is
    the agent's :class:`~goalagent.kb.interpreter_requests.Requests`)."""

    def __init__(self, agent: Agent) -> None:
        self._agent = agent
        self._code = CompiledProgram(agent.ms, agent.program)
        self._calls: list[RunRecord] = []  # the interpreter calls in progress, innermost last
        self._called: list[str] = []  # the modules of the module calls in progress
        self.cycle_plans = _CyclePlans(agent, self._code)

    def run_modules(self, modules: Sequence[tuple[ast.Module, Mapping[str, Term]]], *,
                    count_last: bool = False) -> RunOutcome:
        """One pass over each module's rules, in one interpreter call (the modules run in
        turn; exit-module leaves only its own module); ``count_last``: the outcome counts
        the last module's actions."""
        agent = self._agent
        names = " + ".join(module.name for module, _ in modules)
        depth = agent.ms.limits.max_module_depth
        if len(self._calls) > depth:
            chain = " -> ".join(self._called[-6:])
            raise AgentError(f"module calls nested more than {depth} deep (... -> {chain} -> "
                             f"{names}): a module that calls itself without end? The agent "
                             "is stopped (--max-module-depth)")
        plan = self._code.plan(modules, environment=agent.io is not None,
                               listen=bool(agent.listeners), count_last=count_last)
        self._called.append(names)
        limit = sys.getrecursionlimit()
        if self._calls:  # each nested level is given Python frames of its own
            sys.setrecursionlimit(limit + FRAMES_PER_LEVEL)
        try:
            return self.run_plan(plan)
        finally:
            sys.setrecursionlimit(limit)
            self._called.pop()

    def run_once(self, module: ast.Module) -> RunOutcome:
        """One pass over a module made outside the program (see ``add_module``)."""
        self._code.add_module(module)
        return self.run_modules([(module, {})], count_last=True)

    def run_plan(self, plan: Term | PlanPredicate) -> RunOutcome:
        """Runs a plan (see ``CompiledProgram.plan``; ``cycle_plans`` has the cycles') in
        one interpreter call; the report gets its spans, the agent its action count."""
        agent = self._agent
        record = RunRecord()
        self._calls.append(record)
        try:
            outcome = record.outcome = self._code.run(plan, self)
        finally:
            self._calls.pop()
        report = agent.report
        if record.module_calls:
            report.entries.append(Span(record, record.entries_from))
            report.performed.append(Span(record, record.actions_from))
        else:  # the whole call: the record is its own span
            report.entries.append(record)
            report.performed.append(record)
        report.action_count += outcome.actions
        # Module calls are no actions; a firing a limit ended after a module call is not
        # counted, its call is (hence the bound).
        agent.total_actions += max(outcome.actions - record.module_calls, 0)
        return outcome

    def split_at(self, entries: int, position: int) -> None:
        """A module call at action ``position`` of the running call (``entries`` firings
        done): the report shows the call's firings and actions so far, the call, then what
        the called module does."""
        record = self._calls[-1]
        report = self._agent.report
        report.entries.append(Span(record, record.entries_from, entries))
        report.performed.append(Span(record, record.actions_from, position + 1))
        record.entries_from, record.actions_from = entries, position + 1
        record.module_calls += 1

    # ------------------------------------------------------------------ requests

    def shuffle(self, count: int) -> list[int]:
        order = list(range(count))
        self._agent.random.shuffle(order)
        return order

    def output(self, text: str, log: bool) -> None:
        actions.output(self._agent, text, log)

    def act(self, firing: Firing, index: int, action: Term) -> bool:
        return actions.act_on_environment(self._agent, firing, index, action)

    def send(self, firing: Firing, index: int, once: bool, mood: str, receiver: Term,
             content: Term) -> bool:
        return messages.send(self._agent, firing, index, once, mood, receiver, content)

    def call_module(self, firing: Firing, index: int, module: int, args: list[Term],
                    entries: int, position: int) -> bool:
        agent = self._agent
        return modules.call_module(agent, self, firing, index, agent.program.modules[module],
                                   args, entries, position)

    def goal7(self, name: str, args: list[Term]) -> None:
        timers.perform(self._agent, name, args)

    def problem(self, problem: Problem) -> None:
        self._agent.warn(warning_text(problem, self._agent.program))

    def step(self, step: Step) -> None:
        agent = self._agent
        agent.tell(interpreter_event(agent.name, step, agent.program))
