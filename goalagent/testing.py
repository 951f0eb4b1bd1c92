"""GOAL's agent tests (`.test2g`): run the system a test file names, make its agents take
the steps the file gives (``do main until C.``, GOAL 5's ``do init.``, ``assert C.``,
``evaluate { .. } in do main.``) and judge its temporal conditions (``eventually``,
``always``, ``never``, ``atend``, ``C leadsto D``) over the states the agents pass through,
for module tests (``test m with pre{..} in{..} post{..}``) while module m runs.

A state is an agent's mental state after one of its cycles; ``done(Action)`` holds in it
when the agent performed Action in that cycle. The agents of the system all run, one cycle
each in turn as ``goalagent run`` does, until every agent the test names has taken its
steps (or stopped), the file's ``timeout`` (seconds) passed or ``max_cycles`` ran. Written
here rather than taken from a library because the judging is GOAL's own semantics over
goalagent's mental states.

The agents run with the limits and confinement ``goalagent run`` gives them (``limits``, and
a ``.mas2g``'s own per agent); the test's conditions are judged as the agent's own code,
under its limits: a condition that raises, runs away or is refused fails its item, with the
item's position, and the rest of the file goes on.
"""

from __future__ import annotations

import functools
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from goalagent import ast
from goalagent.agent import Agent, Event, EventKind
from goalagent.kb.engine import KBError, PrologSyntaxError, get_engine
from goalagent.kb.limits import Limits
from goalagent.kb.terms import Term, format_term
from goalagent.mas import MultiAgentSystem
from goalagent.parser import GoalSyntaxError, parse_test_file

Bindings = dict[str, Term]
_MAX_OBLIGATIONS = 1000  # pending `leadsto` instances kept per condition


@dataclass(frozen=True)
class Verdict:
    """One judged item: a condition, a step or a pre/post condition."""

    what: str
    pos: ast.Pos
    passed: bool
    detail: str = ""


@dataclass
class Section:
    """The verdicts of one agent's steps or of one module test on one agent."""

    title: str
    verdicts: list[Verdict] = field(default_factory=list)


@dataclass
class TestReport:
    """What a test file's run found: per section, per item, passed or failed and why."""

    file: str
    sections: list[Section]
    cycles: int = 0

    @property
    def verdicts(self) -> list[Verdict]:
        return [verdict for section in self.sections for verdict in section.verdicts]

    @property
    def passed(self) -> bool:
        """Every item passed (a test block with no tests passes, as in GOAL)."""
        return all(verdict.passed for verdict in self.verdicts)

    def text(self) -> str:
        """The report as lines: per section its items, then the totals."""
        lines = [f"{self.file}:"]
        for section in self.sections:
            lines.append(f"  {section.title}")
            for verdict in section.verdicts:
                mark = "passed" if verdict.passed else "FAILED"
                detail = f" -- {verdict.detail}" if verdict.detail else ""
                lines.append(f"    {mark}  {verdict.what}  ({verdict.pos}){detail}")
        failed = sum(not verdict.passed for verdict in self.verdicts)
        lines.append(f"  {len(self.verdicts) - failed} passed, {failed} failed "
                     f"({self.cycles} cycles)")
        return "\n".join(lines)


def run_test_file(path: str | Path, *, max_cycles: int = 1000, seed: int = 0,
                  output=None, warn=None, limits: Limits | None = None) -> TestReport:
    """Run a `.test2g` file (GoalSyntaxError for a malformed one or one naming what its
    system lacks; the system's own loading errors as ``goalagent run`` raises them), its
    agents under ``limits`` as ``goalagent run`` would."""
    test = parse_test_file(path)
    system = MultiAgentSystem.from_mas_file(test.mas, seed=seed, output=output, warn=warn,
                                            limits=limits)
    try:
        return _TestRun(test, system, max_cycles).run()
    finally:
        system.close()


# ----------------------------------------------------------------------------- judging


class _Judge:
    """Evaluates test conditions on one agent's mental state; ``done`` holds the actions
    the agent performed in its last cycle."""

    def __init__(self, agent: Agent) -> None:
        self.agent = agent
        self.done: list[Term] = []
        self._compiled: dict[int, object] = {}

    def answers(self, condition: ast.Condition, bindings: Bindings | None = None,
                limit: int | None = None) -> list[Bindings]:
        """The answers of ``condition`` (with ``bindings``) in the current state."""
        ms = self.agent.ms
        positive = [lit for lit in condition if isinstance(lit, ast.MentalLiteral)
                    and lit.op == "done"]
        negative = [lit for lit in condition if isinstance(lit, ast.NotLiteral)
                    and all(isinstance(inner, ast.MentalLiteral) and inner.op == "done"
                            for inner in lit.condition)]
        rest = tuple(lit for lit in condition if lit not in positive and lit not in negative)
        candidates: list[Bindings] = [dict(bindings or {})]
        for literal in positive:
            query = literal.query
            assert query is not None  # (done(Action) always has its action)
            candidates = [match for candidate in candidates for action in self.done
                          if (match := ms.unify(query, action, candidate)) is not None]
        results: list[Bindings] = []
        for candidate in candidates:
            solutions = [candidate]
            if rest:
                compiled = self._compiled.get(id(condition))
                if compiled is None:
                    compiled = self._compiled[id(condition)] = ms.compile(rest)
                solutions = ms.solutions(compiled, candidate)  # type: ignore[arg-type]
            for solution in solutions:
                if not any(self._done_matches(inner, solution) for lit in negative
                           for inner in lit.condition):
                    results.append(solution)
                    if limit is not None and len(results) >= limit:
                        return results
        return results

    def _done_matches(self, literal: ast.Literal, bindings: Bindings) -> bool:
        query = literal.query if isinstance(literal, ast.MentalLiteral) else None
        return query is not None and any(self.agent.ms.unify(query, action, bindings) is not None
                                         for action in self.done)

    def holds(self, condition: ast.Condition, bindings: Bindings | None = None) -> bool:
        return bool(self.answers(condition, bindings, limit=1))

    def judge(self, condition: ast.Condition, when: str = "") -> tuple[bool, str]:
        """Whether ``condition`` holds, and why it could not be judged: a Prolog error, a
        limit passed, a refused call (then it does not hold); ``when``: where the error is
        said to be (default: at the agent's cycle)."""
        try:
            return self.holds(condition), ""
        except KBError as err:
            return False, f"a Prolog error {when or f'at cycle {self.agent.cycle}'}: {err}"


class _Monitor:
    """One temporal condition judged state by state on one agent."""

    def __init__(self, condition: ast.TestCondition, judge: _Judge) -> None:
        self.condition = condition
        self.judge = judge
        self.seen = 0  # states observed
        self.at: int | None = None  # when it held (eventually) or was broken (always, never)
        self.pending: dict[str, tuple[int, Bindings]] = {}  # leadsto instances waiting
        self.broken: tuple[int, Bindings] | None = None
        self.error = ""  # a Prolog error evaluating the condition: it fails, judged no more
        self.held: list[int] = []  # watch: the cycles in which it held

    def observe(self, cycle: int) -> None:
        if self.error:
            return
        self.seen += 1
        try:
            self._observe(cycle)
        except KBError as err:  # e.g. a predicate the agent does not define
            self.error = f"a Prolog error at cycle {cycle}: {err}"

    def _observe(self, cycle: int) -> None:
        kind, condition = self.condition.kind, self.condition.condition
        judge = self.judge
        if kind == "eventually" and self.at is None and judge.holds(condition):
            self.at = cycle
        elif kind == "atstart" and self.seen == 1:
            self.at = cycle if judge.holds(condition) else None
        elif kind == "watch" and judge.holds(condition):
            self.held.append(cycle)
        elif kind == "always" and self.at is None and not judge.holds(condition):
            self.at = cycle
        elif kind == "never" and self.at is None and judge.holds(condition):
            self.at = cycle
        elif kind == "leadsto":
            for answer in judge.answers(condition):
                key = repr(sorted((name, format_term(value)) for name, value in answer.items()))
                if key not in self.pending and len(self.pending) < _MAX_OBLIGATIONS:
                    self.pending[key] = (cycle, answer)
            assert self.condition.then is not None
            for key, (_, answer) in list(self.pending.items()):
                if judge.holds(self.condition.then, answer):
                    del self.pending[key]

    def verdict(self) -> Verdict:
        kind, text, pos = self.condition.kind, self.condition.text, self.condition.pos
        if self.error:
            return Verdict(text, pos, False, self.error)
        states = f"{self.seen} state(s)"
        if kind == "eventually":
            return Verdict(text, pos, self.at is not None,
                           f"held at cycle {self.at}" if self.at is not None
                           else f"never held in {states}")
        if kind == "atstart":
            return Verdict(text, pos, self.at is not None, "" if self.at is not None else
                           "did not hold at the start")
        if kind == "watch":  # only watched: reported, never failed
            held = self.held
            return Verdict(text, pos, True, f"held in {len(held)} of {states}"
                           + (f" (cycles {', '.join(map(str, held[:10]))})" if held else ""))
        if kind in ("always", "never"):
            broken = "did not hold" if kind == "always" else "held"
            return Verdict(text, pos, self.at is None,
                           f"{broken} at cycle {self.at}" if self.at is not None else states)
        if kind == "atend":
            at_end, error = self.judge.judge(self.condition.condition, "at the end")
            return Verdict(text, pos, at_end,
                           error or ("" if at_end else "did not hold at the end"))
        if self.pending:
            cycle, answer = next(iter(self.pending.values()))
            shown = ", ".join(f"{n}={format_term(v)}" for n, v in answer.items())
            return Verdict(text, pos, False, f"its left side held at cycle {cycle}"
                           f"{' with ' + shown if shown else ''}, its right side never after")
        return Verdict(text, pos, True, states)


# ----------------------------------------------------------------------------- running


def _module_matches(module: ast.Module, name: str) -> bool:
    """A test names a module by its name, the name its file gives it or its file's name."""
    return name in (module.name, module.declared, Path(module.pos.file).stem)


class _ModuleWatch:
    """A module test on one agent: pre when the module first runs, the conditions after
    every cycle in which it ran, post after the last."""

    def __init__(self, test: ast.ModuleTest, module: ast.Module, judge: _Judge,
                 agent: Agent) -> None:
        self.test = test
        self.module = module
        self.judge = judge
        self.monitors = [_Monitor(condition, judge) for condition in test.conditions]
        self.section = Section(f"test {test.module} (agent {agent.name})")
        self.pre_result: tuple[bool, str] = (False, "")
        self.pre_checked = False
        self.ran = False

    def before_cycle(self) -> None:
        """Judge pre on the state the module is about to start from (kept until it runs)."""
        if self.test.pre is not None and not self.pre_checked:
            self.pre_result = self.judge.judge(self.test.pre)

    def after_cycle(self, cycle: int, ran: bool) -> None:
        if not ran:
            return
        if not self.pre_checked and self.test.pre is not None:
            self.pre_checked = True
            held, error = self.pre_result
            self.section.verdicts.append(Verdict("pre", self.test.pos, held, error or (
                "" if held else f"did not hold when {self.test.module} began")))
        self.ran = True
        for monitor in self.monitors:
            monitor.observe(cycle)

    def finish(self) -> Section:
        if not self.ran:
            self.section.verdicts.append(Verdict(f"module {self.test.module}", self.test.pos,
                                                 False, "never ran"))
            return self.section
        self.section.verdicts.extend(monitor.verdict() for monitor in self.monitors)
        if self.test.post is not None:
            held, error = self.judge.judge(self.test.post)
            self.section.verdicts.append(Verdict("post", self.test.pos, held, error or (
                "" if held else "did not hold when the test ended")))
        return self.section


class _Script:
    """The steps a test makes one agent take, as a generator: it yields once per cycle
    the agent should run; between yields it judges asserts and until conditions."""

    def __init__(self, test: ast.AgentTest, agent: Agent, judge: _Judge, run: _TestRun):
        self.test = test
        self.agent = agent
        self.judge = judge
        self.run = run
        self.section = Section(f"agent {agent.name}")
        self.steps = self._steps()
        self.done = False

    def _steps(self) -> Iterator[None]:
        for step in self.test.steps:
            if step.kind == "assert":
                assert step.condition is not None
                held, error = self.judge.judge(step.condition)
                self.section.verdicts.append(Verdict(
                    f"assert{': ' + step.message if step.message else ''}", step.pos, held,
                    error or ("" if held else "did not hold")))
                continue
            if self._is_init(step):
                self.run.initialize(self.agent)
                continue
            monitors = [_Monitor(condition, self.judge) for condition in step.conditions]
            yield from self._do(step, monitors)
            self.section.verdicts.extend(monitor.verdict() for monitor in monitors)

    def _is_init(self, step: ast.TestStep) -> bool:
        init = self.agent.program.module("init")
        return init is not None and _module_matches(init, step.target) and step.until is None

    def _do(self, step: ast.TestStep, monitors: list[_Monitor]) -> Iterator[None]:
        """``do main [until C]``: cycles until C holds, the agent stops or time is up; the
        conditions are judged in the state main starts from and after every cycle. ``do a
        + b`` of other actions or modules: they are done once."""
        if self.agent.cycle == 0 and not self.agent.initialized_apart:
            self.run.initialize(self.agent)  # GOAL enters main once init has run
        for monitor in monitors:
            monitor.observe(self.agent.cycle)
        main = self.agent.program.module("main")
        if main is None or not _module_matches(main, step.target):
            yield from self._do_once(step, monitors)
            return
        what = f"do {step.target}" + (" until ..." if step.until else "")
        start = self.agent.cycle
        while True:
            held, error = self.judge.judge(step.until) if step.until is not None else (False, "")
            if error:  # its condition cannot be judged: the step fails there
                self.section.verdicts.append(Verdict(what, step.pos, False, error))
                return
            if held:
                self.section.verdicts.append(Verdict(what, step.pos, True, f"reached after "
                                                     f"{self.agent.cycle - start} cycle(s)"))
                return
            if self.agent.terminated or self.run.out_of_time():
                reason = "the agent stopped" if self.agent.terminated else "time ran out"
                passed = step.until is None
                self.section.verdicts.append(Verdict(
                    what, step.pos, passed,
                    f"{reason} after {self.agent.cycle - start} cycle(s)"
                    + ("" if passed else " before its condition held")))
                return
            yield
            for monitor in monitors:
                monitor.observe(self.agent.cycle)

    def _do_once(self, step: ast.TestStep, monitors: list[_Monitor]) -> Iterator[None]:
        """A step doing actions or a module other than main: once, in a turn of its own."""
        actions = step.actions or ((step.action,) if step.action is not None else ())
        self.run.pending[self.agent.name] = (actions, step.pos)
        yield
        for monitor in monitors:
            monitor.observe(self.agent.cycle)
        self.section.verdicts.append(Verdict(f"do {step.target}", step.pos, True,
                                             f"done in cycle {self.agent.cycle}"))

    def advance(self) -> bool:
        """Take the steps up to the next cycle; False when the script is over."""
        if self.done:
            return False
        try:
            next(self.steps)
            return True
        except StopIteration:
            self.done = True
            return False


class _TestRun:
    """One run of a test file's system."""

    def __init__(self, test: ast.TestProgram, system: MultiAgentSystem,
                 max_cycles: int) -> None:
        self.test = test
        self.system = system
        self.max_cycles = max_cycles
        self.deadline = time.monotonic() + test.timeout if test.timeout else None
        self.rounds = 0
        self.entered: dict[str, set[str]] = {}  # per agent: modules entered this cycle
        self.judges = {agent.name: _Judge(agent) for agent in system.agents}
        self.watches: dict[str, list[_ModuleWatch]] = {}
        self.pending: dict[str, tuple] = {}  # per agent: a step's actions to do next turn
        for agent in system.agents:
            agent.listen(self._listener(agent.name))

    def _listener(self, name: str):
        def heard(event: Event) -> None:
            if event.kind is EventKind.MODULE_ENTERED and event.module is not None:
                self.entered.setdefault(name, set()).add(event.module)
        return heard

    def out_of_time(self) -> bool:
        return self.rounds >= self.max_cycles or (
            self.deadline is not None and time.monotonic() > self.deadline)

    def initialize(self, agent: Agent) -> None:
        """GOAL 5's ``do init.``: the init module alone."""
        for watch in self.watches.get(agent.name, []):
            watch.before_cycle()
        agent.initialize()
        self._observe(agent, init_only=True)

    def run(self) -> TestReport:
        agents = {agent.name: agent for agent in self.system.agents}
        scripts: list[_Script] = []
        for agent_test in self.test.agent_tests:
            agent = agents.get(agent_test.agent)
            if agent is None:
                raise GoalSyntaxError.at(agent_test.pos, f"no agent called {agent_test.agent} "
                                         f"in {Path(self.test.mas).name} (agents: "
                                         f"{', '.join(agents) or 'none'})")
            scripts.append(_Script(agent_test, agent, self.judges[agent.name], self))
        tested = [script.agent for script in scripts] or list(agents.values())
        for module_test in self.test.module_tests:
            found = False
            for agent in tested:
                for module in agent.program.modules:
                    if _module_matches(module, module_test.module):
                        found = True
                        self.watches.setdefault(agent.name, []).append(
                            _ModuleWatch(module_test, module, self.judges[agent.name], agent))
            if not found:
                raise GoalSyntaxError.at(module_test.pos, f"test {module_test.module}: no "
                                         "agent of the test has a module of that name")
        waiting = {script.agent.name: script for script in scripts if script.advance()}
        while waiting and not self.out_of_time():
            self.rounds += 1
            for agent in list(self.system.agents):
                if agent.terminated or agent.name in self.system.failures:
                    continue
                if scripts and agent.name not in waiting and agent.name in {
                        s.agent.name for s in scripts}:
                    continue  # its steps are over
                for watch in self.watches.get(agent.name, []):
                    watch.before_cycle()
                pending = self.pending.pop(agent.name, None)
                self.system.step(agent, None if pending is None else
                                 functools.partial(agent.perform, *pending))
                self._observe(agent)
                script = waiting.get(agent.name)
                if script is not None and not script.advance():
                    del waiting[agent.name]
        for script in waiting.values():  # time ran out: let each judge where it is
            while script.advance():
                pass
        sections = [script.section for script in scripts]
        sections += [watch.finish() for watches in self.watches.values() for watch in watches]
        return TestReport(self.test.file, sections, self.rounds)

    def _observe(self, agent: Agent, init_only: bool = False) -> None:
        """After one of ``agent``'s cycles: what it did, then the module tests."""
        judge = self.judges[agent.name]
        judge.done = _performed(agent)
        entered = self.entered.pop(agent.name, set())
        focus = {focus.module.name for focus in agent.focus}
        for watch in self.watches.get(agent.name, []):
            kind = watch.module.kind
            if init_only:
                ran = kind == "init"
            elif kind == "init":
                ran = agent.cycle == 1 and not agent.initialized_apart
            elif kind in ("main", "event"):
                ran = True
            else:
                ran = watch.module.name in entered or watch.module.name in focus
            watch.after_cycle(agent.cycle, ran)


def _performed(agent: Agent) -> list[Term]:
    """The actions the agent performed in its last cycle, as terms (messages left out)."""
    report = agent.last_report
    if report is None:
        return []
    engine = get_engine()
    terms = []
    for fired in report.fired:
        for action in fired.actions:
            try:
                terms.append(engine.parse_term(action))
            except PrologSyntaxError:
                continue  # a message: Receiver.send(..) is no term
    return terms
