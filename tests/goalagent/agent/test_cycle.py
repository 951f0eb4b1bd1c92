"""Reasoning-cycle semantics: which rule fires, with which bindings, in which order."""

from __future__ import annotations

import io

import pytest

from goalagent.agent import Agent, LocalPostman
from goalagent.kb.terms import Atom, Struct
from goalagent.parser import GoalSyntaxError


def make(text: str, **kwargs) -> Agent:
    kwargs.setdefault("output", io.StringIO())
    kwargs.setdefault("warn", lambda message: None)
    return Agent.from_string(text, "test.goal", **kwargs)


class Recorder:
    """An environment seam with no percepts that records the actions sent to it."""

    def __init__(self) -> None:
        self.sent: list[object] = []

    def percepts(self) -> list[object]:
        return []

    def act(self, action: object) -> None:
        self.sent.append(action)


def printed(agent: Agent) -> list[str]:
    return agent.output.getvalue().splitlines()


def test_linear_order_fires_only_the_first_applicable_rule():
    agent = make("""
        init module { beliefs { a. b. } }
        main module { program {
            if bel(c) then print(never).
            if bel(a) then print(first).
            if bel(b) then print(second).
        } }
    """)
    report = agent.step()
    assert printed(agent) == ["first"]
    assert [fired.line for fired in report.fired] == [5]


def test_linearall_fires_every_applicable_rule_once_with_its_first_instantiation():
    agent = make("""
        init module { beliefs { p(1). p(2). q. } }
        main module { program [order=linearall] {
            if bel(p(X)) then print(X).
            if bel(q) then print(q).
        } }
    """)
    agent.step()
    assert printed(agent) == ["1", "q"]


def test_forall_fires_every_instantiation():
    agent = make("""
        init module { beliefs { p(1). p(2). p(3). } }
        main module { program { forall bel(p(X)) do print(X). } }
    """)
    report = agent.step()
    assert printed(agent) == ["1", "2", "3"]
    assert [f.bindings["X"] for f in report.fired] == [1, 2, 3]


def test_random_order_is_reproducible_under_a_seed_and_varies_across_seeds():
    program = """
        main module { program [order=randomall] {
            if true then print(a). if true then print(b). if true then print(c).
            if true then print(d). if true then print(e).
        } }
    """
    runs = {}
    for seed in (1, 1, 2, 3, 4):
        agent = make(program, seed=seed)
        agent.step()
        runs.setdefault(seed, []).append(printed(agent))
    assert runs[1][0] == runs[1][1]
    assert sorted(runs[1][0]) == ["a", "b", "c", "d", "e"]
    assert len({tuple(r[0]) for r in runs.values()}) > 1


def test_rule_fires_with_first_instantiation_whose_action_is_enabled():
    agent = make("""
        init module {
            beliefs { p(1). p(2). ok(2). }
            actionspec { act(X) { pre { ok(X) } post { done(X) } } }
        }
        main module { program { if bel(p(X)) then act(X). } }
    """)
    report = agent.step()
    assert report.fired[0].bindings["X"] == 2
    assert agent.query("bel", "done(X)") == [{"X": 2}]


def test_combo_stops_at_first_action_not_enabled():
    agent = make("""
        init module {
            actionspec { blocked { pre { fail } post { true } } }
        }
        main module { program { if true then print(one) + blocked + print(two). } }
    """)
    report = agent.step()
    assert printed(agent) == ["one"]
    assert report.actions == ["print(one)"]


def test_nested_rules_see_the_outer_bindings():
    agent = make("""
        init module { beliefs { room(r1). room(r2). door(r2, d7). } }
        main module { program [order=linearall] {
            forall bel(room(R)) do {
                if bel(door(R, D)) then print(D).
            }
        } }
    """)
    agent.step()
    assert printed(agent) == ["d7"]


def test_listall_binds_the_list_of_all_answers():
    agent = make("""
        init module { beliefs { p(3). p(1). p(2). } }
        main module { program { listall L <- bel(p(X)) do insert(all(L)). } }
    """)
    agent.step()
    assert agent.query("bel", "all(L)") == [{"L": [3, 1, 2]}]


def test_macro_expands_with_its_arguments_and_fresh_locals():
    agent = make("""
        init module { beliefs { on(a, b). on(b, table). block(a). block(b). } }
        main module { program {
            #define clear(X) bel(block(X), not(on(_, X))).
            if clear(B) then print(B).
        } }
    """)
    agent.step()
    assert printed(agent) == ["a"]


def test_blind_commitment_drops_a_goal_once_all_its_facts_are_believed():
    agent = make("""
        init module { goals { p, q. } }
        main module [exit=nogoals] { program [order=linear] {
            if a-goal(p) then insert(p).
            if a-goal(q) then insert(q).
        } }
    """)
    agent.step()
    assert agent.goals() == [[Atom("p"), Atom("q")]]
    agent.step()
    assert agent.goals() == []
    assert agent.terminated


def test_goal_a_and_a_goal_split_a_goal_into_achieved_and_open_parts():
    agent = make("""
        init module { beliefs { p. } goals { p, q. } }
        main module { program [order=linearall] {
            if goal-a(p) then print(achieved).
            if a-goal(q) then print(open).
            if a-goal(p) then print(wrong).
        } }
    """)
    agent.step()
    assert printed(agent) == ["achieved", "open"]


def test_adopt_is_refused_for_a_believed_formula_and_the_rule_does_not_fire():
    agent = make("""
        init module { beliefs { p. } }
        main module { program { if true then adopt(p). } }
    """)
    report = agent.step()
    assert report.fired == []
    assert agent.goals() == []


def test_drop_removes_every_goal_entailing_the_formula():
    agent = make("""
        init module { goals { p, q. r. p. } }
        main module { program { if true then drop(p). } }
    """)
    agent.step()
    assert agent.goals() == [[Atom("r")]]


def test_percepts_hold_for_the_current_cycle_only():
    class Flicker:
        def __init__(self) -> None:
            self.cycle = 0

        def percepts(self):
            self.cycle += 1
            return [Struct("tick", (self.cycle,))] if self.cycle == 1 else []

        def act(self, action) -> None:
            pass

    agent = make("""
        main module { program [order=linearall] {
            if percept(tick(N)) then print(N).
            if bel(percept(tick(N))) then print(again).
        } }
    """, io=Flicker())
    agent.step()
    agent.step()
    assert printed(agent) == ["1", "again"]


def test_event_module_runs_before_main_each_cycle():
    agent = make("""
        init module { beliefs { n(0). } }
        event module { program {
            if bel(n(N), M is N + 1) then delete(n(N)) + insert(n(M)).
        } }
        main module { program { if bel(n(N)) then print(N). } }
    """)
    agent.step()
    agent.step()
    assert printed(agent) == ["1", "2"]


def test_init_module_runs_once():
    agent = make("""
        init module { program { if true then print(init). } }
        main module { program { if true then print(main). } }
    """)
    agent.run(max_cycles=3)
    assert printed(agent) == ["init", "main", "main", "main"]


def test_exit_noaction_stops_when_main_does_nothing():
    agent = make("""
        init module { beliefs { left(2). } }
        main module [exit=noaction] { program {
            if bel(left(N), N > 0, M is N - 1) then delete(left(N)) + insert(left(M)).
        } }
    """)
    result = agent.run(max_cycles=10)
    assert result.terminated and result.cycles == 3


def test_user_module_with_parameters_is_called_as_an_action():
    agent = make("""
        module greet(Who) { program { if true then print(Who). } }
        main module { program { if bel(X = world) then greet(X). } }
    """)
    report = agent.step()
    assert printed(agent) == ["world"]
    assert report.actions[0] == "greet(world)"


def test_exit_module_leaves_the_module_at_once():
    agent = make("""
        module sub { program [order=linearall] {
            if true then print(a) + exit-module.
            if true then print(b).
        } }
        main module { program { if true then sub. } }
    """)
    agent.step()
    assert printed(agent) == ["a"]


def test_focus_new_gives_the_module_its_own_goal_base():
    agent = make("""
        init module { goals { outer. } }
        module sub [focus=new, exit=nogoals] { program {
            if true then adopt(inner).
        } }
        main module { program { if goal(outer) then sub. } }
    """)
    agent.step()
    assert agent.goals() == [[Atom("inner")]]


def test_actions_without_environment_act_through_postconditions():
    agent = make("""
        init module {
            beliefs { on(a, table). }
            actionspec { move(X, Y) { pre { on(X, Z) } post { not(on(X, Z)), on(X, Y) } } }
        }
        main module { program { if bel(on(a, table)) then move(a, b). } }
    """)
    agent.step()
    assert agent.query("bel", "on(a, Y)") == [{"Y": Atom("b")}]


def test_internal_actions_are_not_sent_to_the_environment():
    recorder = Recorder()

    agent = make("""
        init module { actionspec {
            skip@int { pre { true } post { true } }
            go(X) { pre { true } post { went(X) } }
        } }
        main module { program [order=linearall] {
            if true then skip. if true then go(home).
        } }
    """, io=recorder)
    agent.step()
    assert recorder.sent == [Struct("go", (Atom("home"),))]


def test_prolog_error_in_a_condition_is_a_warning_and_the_agent_goes_on():
    warnings = []
    agent = make("""
        main module { program [order=linearall] {
            if bel(X is foo + 1) then print(X).
            if true then print(still_running).
        } }
    """, warn=warnings.append)
    agent.step()
    assert printed(agent) == ["still_running"]
    assert any("test.goal:3" in w and "Prolog error" in w for w in warnings)


def test_unknown_action_is_a_located_error():
    with pytest.raises(GoalSyntaxError) as err:
        make("main module { program {\n if true then fly(away). } }")
    assert str(err.value).startswith("test.goal:2:15: unknown action fly/1")


def test_messages_between_two_agents_with_moods():
    postman = LocalPostman()
    for name in ("alice", "bob"):
        postman.register(name)
    alice = make("""
        main module { program [order=linearall] {
            if true then bob.sendonce(:fact(1)).
            if true then bob.sendonce(!want(2)).
            if true then bob.sendonce(?ask(3)).
        } }
    """, name="alice", postman=postman)
    bob = make("""
        main module { program {
            forall bel(received(S, M)) do insert(got(S, M)).
        } }
    """, name="bob", postman=postman)
    alice.step()
    alice.step()  # sendonce: nothing new is sent
    bob.step()
    got = sorted(str(answer["M"]) for answer in bob.query("bel", "got(alice, M)"))
    assert got == ["fact(1)", "imp(want(2))", "int(ask(3))"]
    assert len(alice.query("bel", "sent(bob, M)")) == 3


@pytest.mark.parametrize("traced", [False, True])
def test_an_environment_action_whose_postcondition_fails_still_happened(traced):
    recorder = Recorder()
    warnings = []

    agent = make("""
        init module {
            beliefs { p(1). p(2). }
            actionspec { go(X) { pre { true } post { done(X, _) } } }
        }
        main module { program { if bel(p(X)) then go(X) + print(after(X)). } }
    """, io=recorder, warn=warnings.append,
         tracer=(lambda agent, kind, text: None) if traced else None)
    agent.step()
    assert recorder.sent == [Struct("go", (1,))]  # performed once, not retried with X = 2
    assert printed(agent) == ["after(1)"]
    assert any("go failed" in warning for warning in warnings)
