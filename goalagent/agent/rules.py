"""Rule application: an agent's modules run on the one rule interpreter
(``goalagent.kb.interpreter``), whose requests are answered here -- environment actions,
print/log, messages, module calls, the agent's random rule order, warnings and events --
and whose journals become the cycle report's spans."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

from goalagent import ast
from goalagent.agent import actions, messages, modules
from goalagent.agent.events import interpreter_event
from goalagent.agent.problems import warning_text
from goalagent.agent.reports import RunRecord, Span
from goalagent.kb.interpreter import CompiledProgram, Firing, Journal, Problem, RunOutcome, Step
from goalagent.kb.terms import Term

if TYPE_CHECKING:
    from goalagent.agent.cycle import Agent


class _RunningCall:
    """An interpreter call in progress: its journal's record and where the report's next
    spans of it start (a module call splits them), and its module calls so far."""

    __slots__ = ("record", "entries", "actions", "module_calls")

    def __init__(self) -> None:
        self.record = RunRecord()
        self.entries = 0
        self.actions = 0
        self.module_calls = 0


class RuleApplication:
    """Runs one agent's modules on the interpreter and answers what it asks (this object is
    the agent's :class:`~goalagent.kb.interpreter.Requests`)."""

    def __init__(self, agent: Agent) -> None:
        self._agent = agent
        self._code = CompiledProgram(agent.ms, agent.program)
        self._calls: list[_RunningCall] = []

    def run_modules(self, modules: Sequence[tuple[ast.Module, Mapping[str, Term]]]
                    ) -> RunOutcome:
        """One pass over each module's rules, in one interpreter call (the modules run in
        turn; exit-module leaves only its own module)."""
        agent = self._agent
        call = _RunningCall()
        self._calls.append(call)
        try:
            outcome = self._code.run([(self._code.code(module), bindings)
                                      for module, bindings in modules], self,
                                     environment=agent.io is not None,
                                     listen=bool(agent.listeners))
        except BaseException:
            call.record.journal = Journal()  # spans made by module calls stay readable
            raise
        finally:
            self._calls.pop()
        call.record.journal = outcome.journal
        report = agent.report
        report.entries.append(Span(call.record, call.entries))
        report.performed.append(Span(call.record, call.actions))
        report.action_count += outcome.actions
        agent.total_actions += outcome.actions - call.module_calls  # calls are no actions
        return outcome

    def split_at(self, entries: int, position: int) -> None:
        """A module call at action ``position`` of the running call (``entries`` firings
        done): the report shows the call's firings and actions so far, the call, then what
        the called module does."""
        call = self._calls[-1]
        report = self._agent.report
        report.entries.append(Span(call.record, call.entries, entries))
        report.performed.append(Span(call.record, call.actions, position + 1))
        call.entries, call.actions = entries, position + 1
        call.module_calls += 1

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

    def problem(self, problem: Problem) -> None:
        self._agent.warn(warning_text(problem, self._agent.program))

    def step(self, step: Step) -> None:
        agent = self._agent
        agent.tell(interpreter_event(agent.name, step, agent.program))
