"""The one rule interpreter: every rule runs compiled in Prolog, a cycle's modules in one
call; listeners (the trace) observe that same path, so a run with and without them gives
the same firings, bindings, actions, beliefs, goals, output and warnings."""

from __future__ import annotations

import io
import re
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings

import goalagent.kb.engine as engine_module
from goalagent.agent import Agent, AgentError
from goalagent.kb.engine import KBError
from goalagent.kb.terms import Atom, Struct, Term
from goalagent.parser import GoalSyntaxError
from tests.goalagent.agent.test_fuzz_programs import mutated

REFERENCE = Path(__file__).resolve().parents[3] / "bench" / "reference_agent.goal"


def make(text: str, *, traced: bool = False, **kwargs) -> Agent:
    """An agent, with a tracer (its interpreter then tells every step) when ``traced``."""
    kwargs.setdefault("output", io.StringIO())
    warnings: list[str] = []
    kwargs.setdefault("warn", warnings.append)
    if traced:
        kwargs["tracer"] = lambda agent, kind, text: None
    agent = Agent.from_string(text, "test.goal", **kwargs)
    agent.test_warnings = warnings  # type: ignore[attr-defined]
    return agent


def history(agent: Agent, cycles: int) -> list[tuple]:
    """Per cycle: each fired rule's line, bindings and actions, then beliefs and goals."""
    steps = []
    for _ in range(cycles):
        if agent.terminated:
            break
        report = agent.step()
        steps.append([(f.module, f.line, f.bindings, f.actions) for f in report.fired])
        steps.append(report.actions)
    steps.append((agent.beliefs(), agent.goals()))
    return steps


COMBOS = """
init module {
    knowledge { clear(X) :- block(X), \\+ on(_, X). }
    beliefs { block(a). block(b). block(c). on(a, b). n(1). n(2). n(3). p. }
    goals { clear(b). }
}
event module { program {
    forall bel(n(X), Y is X * 10) do insert(m(X, Y)) + delete(n(X)).
    if bel(on(X, Y)) then delete(on(X, Y)) + adopt(clear(Y)) + insert(never).
} }
main module { program [order=linearall] {
    if bel(p) then insert(q) + delete(q) + adopt(q).
    if bel(m(X, _)) then adopt(m(X, 0)) + insert(chosen(X)).
    if a-goal(m(X, Y)) then insert(m(X, Y)).
} }
"""


@pytest.mark.parametrize("text", [COMBOS, REFERENCE.read_text()])
def test_runs_with_and_without_a_tracer_do_the_same(text: str) -> None:
    fast, traced = make(text), make(text, traced=True)
    try:
        assert history(fast, 25) == history(traced, 25)
        assert fast.test_warnings == traced.test_warnings == []  # type: ignore[attr-defined]
    finally:
        fast.close()
        traced.close()


def line_of(text: str, start: str) -> int:
    """The line of ``text`` that starts (after blanks) with ``start``."""
    return next(number for number, line in enumerate(text.splitlines(), 1)
                if line.strip().startswith(start))


def test_a_combo_stops_at_the_first_action_not_enabled() -> None:
    agent = make(COMBOS)
    report = agent.step()
    on, p, m = (line_of(COMBOS, start) for start in ("if bel(on", "if bel(p)", "if bel(m("))
    fired = {f.line: f for f in report.fired}
    # delete(on(a, b)) makes clear(b) believed: adopt(clear(b)) is refused, so the combo
    # stops there and insert(never) is not performed.
    assert fired[on].actions == ("delete(on(a, b))",)
    assert agent.query("bel", "never") == []
    # insert(q) + delete(q) leave q unbelieved, so adopt(q) is enabled.
    assert fired[p].actions == ("insert(q)", "delete(q)", "adopt(q)")
    # adopt(m(X, 0)) is refused for no X (m(X, 0) is never believed), so insert follows;
    # which X fires first is the agent's random choice among the three.
    first = fired[m].bindings["X"]
    assert first in (1, 2, 3)
    assert fired[m].actions == (f"adopt(m({first}, 0))", f"insert(chosen({first}))")
    second = agent.step()
    # Now adopt(m(first, 0)) is refused (already a goal): another instantiation fires.
    [again] = [f.bindings["X"] for f in second.fired if f.line == m]
    assert again in (1, 2, 3) and again != first
    assert on not in [f.line for f in second.fired]  # no on/2 left


def test_blind_commitment_runs_after_each_action_of_a_combo() -> None:
    agent = make("""
        init module { beliefs { go. } goals { p. } }
        main module { program {
            if bel(go) then insert(p) + delete(p) + adopt(p) + delete(go).
        } }
    """)
    report = agent.step()
    # insert(p) achieves the goal p, which is dropped before delete(p); so adopt(p) finds
    # neither the belief nor the goal and is enabled.
    assert report.fired[0].actions == ("insert(p)", "delete(p)", "adopt(p)", "delete(go)")
    assert agent.goals() == [[Atom("p")]]


class Percepts:
    """An environment that shows ``seen`` from the second cycle on."""

    def __init__(self) -> None:
        self.calls = 0

    def percepts(self) -> list[Term]:
        self.calls += 1
        return [Atom("seen")] if self.calls > 1 else []

    def act(self, action: Struct | Atom) -> None:
        """No actions in this test."""


def test_goals_achieved_through_percepts_go_after_the_first_action() -> None:
    agent = make("""
        init module { knowledge { ok :- percept(seen). } goals { ok. } }
        event module { program {
            if true then insert(tick).
            if goal(ok) then insert(still_a_goal).
        } }
    """, io=Percepts())
    agent.step()
    assert agent.query("bel", "still_a_goal") == [{}]
    agent.step()  # insert(tick) changes nothing, but it is the first action after new percepts
    assert agent.goals() == []
    assert agent.last_report is not None
    assert [f.line for f in agent.last_report.fired] == [4]


def test_errors_in_a_pass_are_located_warnings_and_the_pass_goes_on() -> None:
    agent = make("""
        init module { beliefs { n(1). n(2). } }
        main module { program [order=linearall] {
            if bel(X is foo + 1) then insert(x(X)).
            forall bel(n(X)) do insert(m(X, Y)).
            if bel(n(X)) then insert(ok(X)).
        } }
    """)
    report = agent.step()
    warnings = agent.test_warnings  # type: ignore[attr-defined]
    assert "rule at test.goal:4" in warnings[0] and "not applicable" in warnings[0]
    assert len(warnings) == 3
    assert all("test.goal:5:33: insert failed" in w and "not ground" in w for w in warnings[1:])
    assert [f.line for f in report.fired] == [6]
    assert report.actions == ["insert(ok(1))"]


def test_linear_order_stops_inside_a_pass_at_the_first_rule_that_fires() -> None:
    agent = make("""
        main module { program {
            if bel(missing) then insert(a).
            if true then insert(b).
            if true then insert(c).
        } }
    """)
    report = agent.step()
    assert [f.line for f in report.fired] == [4]
    assert agent.query("bel", "b") == [{}] and agent.query("bel", "c") == []


def test_prolog_part_then_python_part_of_a_combo() -> None:
    agent = make("""
        init module { beliefs { n(7). } }
        main module { program {
            if bel(n(X)) then insert(m(X)) + print(X) + insert(k(X)) + adopt(m(X)) + print(no).
        } }
    """)
    report = agent.step()
    assert agent.output.getvalue().splitlines() == ["7"]
    assert report.actions == ["insert(m(7))", "print(7)", "insert(k(7))"]
    assert report.fired[0].bindings == {"X": 7}


def test_rules_of_a_module_with_parameters_get_their_bindings() -> None:
    agent = make("""
        module note(X) { program { if bel(Y is X * 2) then insert(got(X, Y)) + insert(z(X)). } }
        main module [exit=always] { program { if true then note(21). } }
    """)
    agent.step()
    assert agent.query("bel", "got(X, Y), z(Z)") == [{"X": 21, "Y": 42, "Z": 21}]


def test_a_reference_cycle_is_one_prolog_call(monkeypatch) -> None:
    """The event module (2 forall rules) and the main module (4 rules, linearall) run in
    one Prolog call; no other call happens in a cycle of the reference agent."""
    agent = make(REFERENCE.read_text())
    agent.run(3)
    calls = []
    engine = agent.ms.engine

    def counted(original):
        def counting(*args, **kwargs):
            calls.append(args[0])
            return original(*args, **kwargs)
        return counting

    for name in ("solve", "call_once"):  # every way the engine runs a Prolog query
        monkeypatch.setattr(engine, name, counted(getattr(engine, name)))
    for _ in range(10):
        agent.step()
    assert len(calls) == 10
    assert agent.query("bel", "cycle(C)") == [{"C": 13}]
    agent.close()


def test_unread_journals_are_freed_in_prolog() -> None:
    agent = make(REFERENCE.read_text())
    agent.run(5)
    engine = agent.ms.engine
    agent.run(6)  # the previous report's records are released, then erased at the next call
    assert len(engine._dead_records) <= 12
    agent.step()
    agent.query("bel", "true")
    assert engine._dead_records == []
    agent.close()


def test_engine_records_convert_once() -> None:
    engine = engine_module.get_engine()
    pred = engine.predicate("=", 2, "system")
    [[record]] = engine.solve(pred, 2, [(0, Struct("f", (1, Atom("a"))))], 1, outputs=(1,),
                              keep=1)
    assert isinstance(record, engine_module.Record)
    assert record.value() == Struct("f", (1, Atom("a")))
    assert record.value() == Struct("f", (1, Atom("a")))


STACKER = """
init module {
    knowledge {
        clear(table).
        clear(X) :- block(X), \\+ on(_, X).
        tower([X]) :- on(X, table).
        tower([X, Y | T]) :- on(X, Y), tower([Y | T]).
    }
    beliefs { block(a). block(b). block(c). on(a, table). on(b, a). on(c, table). }
    goals { on(a, b), on(b, c), on(c, table). }
}
main module [exit=nogoals] { program {
    if a-goal(tower([X, Y | T])), bel(tower([Y | T])) then move(X, Y) + note(X).
    if a-goal(tower([X | T])) then move(X, table).
} actionspec {
    move(X, Y) { pre { clear(X), clear(Y), on(X, Z), X \\= Y } post { not(on(X, Z)), on(X, Y) } }
    note(X)@int { pre { true } post { moved(X) } }
} }
"""


def test_user_actions_without_environment_act_through_their_postconditions() -> None:
    fast, traced = make(STACKER), make(STACKER, traced=True)
    try:
        assert history(fast, 8) == history(traced, 8)
        assert fast.terminated and traced.terminated
        assert fast.query("bel", "tower([a, b, c])") == [{}]
        assert fast.query("bel", "moved(X)") == [{"X": Atom("b")}, {"X": Atom("a")}]
    finally:
        fast.close()
        traced.close()


class Recorder:
    """An environment that records the actions it is asked to perform."""

    def __init__(self) -> None:
        self.done: list[str] = []

    def percepts(self) -> list[Term]:
        return []

    def act(self, action: Struct | Atom) -> None:
        self.done.append(str(action))


def test_with_an_environment_only_internal_actions_skip_it() -> None:
    env = Recorder()
    agent = make(STACKER, io=env)
    agent.run(8)
    assert agent.terminated
    assert env.done == ["move(b,c)", "move(a,b)"]
    assert agent.query("bel", "moved(X)") == [{"X": Atom("b")}, {"X": Atom("a")}]


@pytest.mark.parametrize("traced", [False, True])
def test_user_action_problems_are_warnings(traced: bool) -> None:
    agent = make("""
        init module { beliefs { n(1). } }
        main module [exit=always] { program [order=linearall] {
            if bel(n(X)) then crash(X) + insert(never).
            if bel(n(X)) then free(X, Y) + insert(never).
            if bel(n(X)) then bad(X) + insert(never).
            if bel(X = X) then open(X) + insert(never).
        } actionspec {
            crash(X) { pre { X > foo } post { true } }
            crash(X) { pre { true } post { crashed(X) } }
            free(X, Y) { pre { true } post { true } }
            bad(X) { pre { true } post { bad(X, _) } }
            open(X) { pre { true } post { true } }
        } }
    """, traced=traced)
    report = agent.step()
    warnings = agent.test_warnings  # type: ignore[attr-defined]
    assert "precondition of crash at test.goal:9:13: Prolog error" in warnings[0]
    assert "test.goal:5:31: action free(1,_" in warnings[1]
    assert "not closed after its precondition" in warnings[1]
    assert "test.goal:6:31: bad failed" in warnings[2] and "not ground" in warnings[2]
    assert "test.goal:7:32: action open(_" in warnings[3]
    assert len(warnings) == 4
    # crash(1) is done through its second spec; the other user actions are not enabled.
    assert report.actions == ["crash(1)", "insert(never)"]
    assert agent.query("bel", "crashed(1)") == [{}]


@pytest.mark.parametrize("order", ["random", "randomall"])
def test_random_orders_in_one_pass_follow_the_seed(order: str) -> None:
    text = f"""
        init module {{ beliefs {{ n(0). }} }}
        main module {{ program [order={order}] {{
            if bel(n(N), M is N + 1) then delete(n(N)) + insert(n(M)) + insert(a(N)).
            if bel(n(N), N mod 2 =:= 0) then insert(even(N)).
            if bel(n(N)) then insert(seen(N)).
            forall bel(a(K), K < 3) do insert(early(K)).
        }} }}
    """
    fast, traced, other = make(text, seed=7), make(text, seed=7, traced=True), make(text, seed=8)
    try:
        fast_history = history(fast, 20)
        assert fast_history == history(traced, 20)
        assert fast_history != history(other, 20)
    finally:
        for agent in (fast, traced, other):
            agent.close()


def test_a_user_action_may_be_called_do() -> None:
    agent = make("""
        init module { beliefs { n(3). } }
        main module [exit=always] { program { if bel(n(X)) then do(X) + insert(after(X)). }
            actionspec { do(X) { pre { Y is X + 1 } post { did(X, Y) } } } }
    """)
    report = agent.step()
    assert report.actions == ["do(3)", "insert(after(3))"]
    assert agent.query("bel", "did(3, Y), after(3)") == [{"Y": 4}]


def _outcome(text: str, traced: bool) -> str:
    """Everything a run of a (possibly broken) program shows: load error, or per cycle the
    fired rules and actions, then beliefs, goals, output and warnings (the numbers of
    fresh variables left out: listening converts more terms)."""
    try:
        agent = make(text, traced=traced)
    except (GoalSyntaxError, AgentError) as err:
        return f"load: {err}"
    steps: list = []
    try:
        for _ in range(6):
            if agent.terminated:
                break
            try:
                report = agent.step()
            except (AgentError, KBError) as err:
                steps.append(("error", str(err)))
                break
            steps.append(([(f.module, f.line, f.bindings, f.actions) for f in report.fired],
                          report.actions))
        steps.append((agent.beliefs(), agent.goals(), agent.output.getvalue(),
                      agent.test_warnings))  # type: ignore[attr-defined]
    finally:
        agent.close()
    return re.sub(r"_G\d+", "_G", repr(steps))


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated())
def test_mutated_programs_run_alike_with_and_without_a_tracer(text: str) -> None:
    assert _outcome(text, traced=False) == _outcome(text, traced=True)


def test_environment_actions_checked_in_prolog_and_performed_by_python() -> None:
    """move/2 goes to the environment: the interpreter checks its precondition, Python
    sends it, the postcondition follows, then the rest of the combo (note@int) runs."""
    fast_env, traced_env = Recorder(), Recorder()
    fast, traced = make(STACKER, io=fast_env), make(STACKER, io=traced_env, traced=True)
    try:
        assert history(fast, 8) == history(traced, 8)
        assert fast_env.done == traced_env.done == ["move(b,c)", "move(a,b)"]
        assert fast.query("bel", "moved(X)") == [{"X": Atom("b")}, {"X": Atom("a")}]
    finally:
        fast.close()
        traced.close()
