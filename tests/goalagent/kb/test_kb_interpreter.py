"""The rule interpreter seen from goalagent.kb: compiled programs, one call per run, the
journal of firings, and the requests Prolog makes of Python (answered here by a recorder
instead of an agent)."""

from __future__ import annotations

import pytest

from goalagent.events import EventKind, ProblemKind
from goalagent.kb.interpreter import CompiledProgram
from goalagent.kb.interpreter_requests import Firing, Problem, Step
from goalagent.kb.mentalstate import MentalState
from goalagent.kb.terms import Atom, Struct, Term
from goalagent.parser import parse_agent


class Recorder:
    """Answers the interpreter's requests and keeps them."""

    def __init__(self, act: bool = True) -> None:
        self.requests: list[tuple] = []
        self.steps: list[Step] = []
        self.problems: list[Problem] = []
        self._act = act

    def shuffle(self, count: int) -> list[int]:
        self.requests.append(("shuffle", count))
        return list(reversed(range(count)))

    def output(self, text: str, log: bool) -> None:
        self.requests.append(("log" if log else "print", text))

    def act(self, firing: Firing, index: int, action: Term) -> bool:
        self.requests.append(("act", firing.bindings, index, action))
        if isinstance(action, Struct) and action.args == (Atom("stop"),):
            raise KeyboardInterrupt
        return self._act

    def send(self, firing, index, once, mood, receiver, content) -> bool:
        self.requests.append(("send", once, mood, receiver, content))
        return True

    def call_module(self, firing, index, module, args, entries, position) -> bool:
        self.requests.append(("call", module, args, entries, position))
        return True

    def problem(self, problem: Problem) -> None:
        self.problems.append(problem)

    def step(self, step: Step) -> None:
        self.steps.append(step)


def run(code: CompiledProgram, program, requests: Recorder, *, environment: bool,
        listen: bool):
    """Runs the program's main module once."""
    plan = code.plan([(program.module("main"), {})], environment=environment, listen=listen)
    return code.run(plan, requests)


PROGRAM = """
init module {
    beliefs { n(1). n(2). n(3). }
    actionspec { go(X) { pre { X > 1 } post { went(X) } } }
}
main module { program [order=linearall] {
    forall bel(n(X), X > 1) do insert(m(X)).
    if bel(n(X)) then go(X) + print(X) + sub(X).
    if bel(Y is 1 / 0) then insert(never).
    if true then bob.send(!hello(world)).
} }
module sub(Z) { program { if true then log(Z). } }
"""


@pytest.fixture
def compiled():
    program = parse_agent(PROGRAM, "t.goal")
    with MentalState("t", beliefs=program.beliefs) as state:
        state.declare_updates([spec.post for spec in program.actionspecs]
                              + [program.modules[1].rules[0].actions[0].args[0]])
        yield program, state, CompiledProgram(state, program)


def test_one_call_runs_a_module_and_keeps_a_journal(compiled) -> None:
    program, state, code = compiled
    requests = Recorder()
    outcome = run(code, program, requests, environment=True, listen=False)
    # forall: m(2), m(3); if: its three instantiations in the order the agent draws (the
    # recorder reverses), go(3) sent + print + module call; send.
    assert outcome.actions == 2 + 3 + 1 and not outcome.exited
    entries = outcome.entries()
    assert [(e.rule.rule.pos.line, e.bindings, e.done) for e in entries] == [
        (7, {"X": 2}, 1), (7, {"X": 3}, 1), (8, {"X": 3}, 3), (10, {}, 1)]
    assert requests.requests == [
        ("shuffle", 3),
        ("act", {"X": 3}, 0, Struct("go", (3,))),
        ("print", "3"),
        ("call", 2, [3], 2, 4),  # after 2 firings, at the 5th action of the call
        ("send", False, "!", Atom("bob"), Struct("hello", (Atom("world"),))),
    ]
    [problem] = requests.problems
    assert problem.kind is ProblemKind.CONDITION_ERROR and problem.rule.rule.pos.line == 9
    assert "zero" in str(problem.detail)
    assert state.query("bel", "went(X)") == [{"X": 3}]
    assert requests.steps == []  # nobody listens


def test_listening_tells_every_step(compiled) -> None:
    program, state, code = compiled
    requests = Recorder()
    run(code, program, requests, environment=False, listen=True)
    kinds = [step.kind for step in requests.steps]
    assert kinds[:4] == [EventKind.RULE_TRIED, EventKind.BELIEF_ADDED,
                         EventKind.RULE_FIRED, EventKind.BELIEF_ADDED]
    tried = [s for s in requests.steps if s.kind is EventKind.RULE_TRIED]
    assert tried[0].bindings == ({"X": 2}, {"X": 3})  # forall: Prolog's order
    assert tried[1].bindings == ({"X": 3}, {"X": 2}, {"X": 1})  # if: the drawn order
    assert not any(s.kind is EventKind.PRECONDITION_FAILED for s in requests.steps)
    assert ("act", {"X": 3}, 0, Struct("go", (3,))) not in requests.requests  # no env


def test_an_if_rule_takes_the_first_enabled_instantiation_in_the_drawn_order(
        compiled) -> None:
    """The agent's order puts X = 1 first: go(1) is not enabled, so go(3) (next) fires."""
    program, state, code = compiled

    class OneFirst(Recorder):
        def shuffle(self, count: int) -> list[int]:
            self.requests.append(("shuffle", count))
            return [0, 2, 1] if count == 3 else list(range(count))

    requests = OneFirst()
    run(code, program, requests, environment=False, listen=True)
    failed = next(s for s in requests.steps if s.kind is EventKind.PRECONDITION_FAILED)
    assert failed.term == Struct("go", (1,)) and failed.spec_index == 0
    fired = [s for s in requests.steps if s.kind is EventKind.RULE_FIRED
             and s.rule.rule.pos.line == 8]
    assert [s.bindings for s in fired] == [({"X": 3},)]
    assert requests.requests.count(("shuffle", 3)) == 1  # only rules with several


def test_random_order_asks_for_a_shuffle_and_follows_it() -> None:
    program = parse_agent("""
        main module { program [order=randomall] {
            if true then print(a). if true then print(b). if true then print(c).
        } }""", "r.goal")
    with MentalState("r") as state:
        code = CompiledProgram(state, program)
        requests = Recorder()
        run(code, program, requests, environment=False, listen=False)
    assert requests.requests == [("shuffle", 3), ("print", "c"), ("print", "b"),
                                 ("print", "a")]


def test_a_python_exception_leaves_prolog_unchanged(compiled) -> None:
    """Ctrl-C inside an environment action ends the run with KeyboardInterrupt itself."""
    program = parse_agent("""
        init module { actionspec { halt(X) { pre { true } post { true } } } }
        main module { program { if true then halt(stop) + print(after). } }""", "h.goal")
    with MentalState("h") as state:
        code = CompiledProgram(state, program)
        requests = Recorder()
        with pytest.raises(KeyboardInterrupt):
            run(code, program, requests, environment=True, listen=False)
        assert ("print", "after") not in requests.requests
        assert state.query("bel", "true") == [{}]  # the engine is usable afterwards
