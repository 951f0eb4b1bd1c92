"""Constructs of GOAL that public programs use, read and run with GOAL's semantics (issue 26):
module parameters in a module's goals, capitalised module/action/macro names, selectors
on messages and mental literals, GOAL 3's percept rules and nested modules, identifiers
that start with a keyword. Each program is written for the test; the comment says which
GOAL runtime or grammar test it re-states."""

from __future__ import annotations

import io
import textwrap

import pytest

from goalagent.agent import Agent
from goalagent.kb.engine import get_engine
from goalagent.parser import (
    GoalSyntaxError,
    load_agents,
    parse_agent,
    parse_agent_file,
    parse_mas,
    parse_mas_file,
    parse_test,
)


def run_agent(text: str, cycles: int = 5) -> tuple[list[str], Agent]:
    """The lines the agent prints in ``cycles`` cycles (it is closed afterwards)."""
    agent = Agent.from_string(textwrap.dedent(text), "c.goal", output=io.StringIO(),
                              warn=lambda message: None)
    try:
        agent.run(max_cycles=cycles)
        return agent.output.getvalue().splitlines(), agent
    finally:
        agent.close()


def test_module_parameters_instantiate_the_goals_adopted_when_it_is_entered() -> None:
    # GOAL's runtime test modulevaringoal.goal: the parameter reaches the module's goal base
    lines, agent = run_agent("""
        main module [exit=nogoals] {
            program {
                if bel(result(X)) then exit-module.
                if bel(true) then test(12).
            }
        }
        module test(X) [focus=new, exit=always] {
            goals { aap(X). }
            program [order=linear] {
                if goal(aap(Y)), bel(Y == 12) then insert(result(ok)) + print(ok).
                if bel(true) then insert(result(failure)) + print(failure).
            }
        }
    """)
    assert lines == ["ok"]


def test_a_module_goal_is_not_adopted_before_the_module_is_entered() -> None:
    lines, _ = run_agent("""
        main module [exit=always] {
            program { if goal(g(_)) then print(early). if true then print(none). }
        }
        module m(X) { goals { g(X). } program { if true then print(X). } }
    """, cycles=1)
    assert lines == ["none"]


def test_a_variable_that_is_no_parameter_in_a_module_goal_is_an_error_at_its_place() -> None:
    with pytest.raises(GoalSyntaxError, match=r"c.goal:2:23: goal g\(X, Y\) is not ground "
                       r"\(variable\(s\) Y\): only the module's parameters"):
        Agent.from_string("main module { program { if true then m(1). } }\n"
                          "module m(X) { goals { g(X, Y). } program { if true then print(X). } }",
                          "c.goal")


def test_capitalised_module_action_and_macro_names_are_names() -> None:
    # GOAL's grammar reads an identifier of either case as a module, action or macro name
    lines, _ = run_agent("""
        init module {
            beliefs { ready. }
            actionspec { Say(X) @int { pre { true } post { said(X) } } }
        }
        main module [exit=always] {
            program [order=linearall] {
                #define Ready bel(ready).
                if Ready then GenericPercepts + Say(hi).
                if bel(said(W)) then print(said(W)).
            }
        }
        module GenericPercepts { program { if true then print(generic). } }
    """, cycles=1)
    assert lines == ["generic", "said(hi)"]


def test_quoted_atom_receivers_and_senders() -> None:
    program = parse_agent(textwrap.dedent("""
        main module {
            program {
                if true then ('control').send(hello).
                if ('control').sent(ok) then print(ok).
            }
        }
    """), "q.goal")
    first, second = program.module("main").rules
    assert first.actions[0].receiver.text == "'control'"
    assert second.condition[0].query.text.startswith("received('control', (ok")


def test_selectors_on_mental_literals_name_this_agent_or_what_another_told() -> None:
    # GOAL's grammar test test.goal: self.bel(..) and (X).bel(..) in a module mod(X)
    # (me/1 believed as a system of agents makes it)
    lines, _ = run_agent("""
        init module { beliefs { me(c). on(a, b). received(bob, on(c, d)). } goals { g. } }
        main module [exit=always] {
            program [order=linearall] {
                if self.bel(on(a, B)) then print(self(B)).
                if bel(me(Me)) then mod(Me).
                if (bob).bel(on(C, d)) then print(told(C)).
                if self.goal(g), this.a-goal(g) then print(goal).
            }
        }
        module mod(X) { program { if (X).bel(on(a, b)) then print(me(X)). } }
    """, cycles=1)
    assert lines == ["self(b)", "me(c)", "told(c)", "goal"]


def test_goal_3_percept_rules_fire_for_every_instantiation_before_the_program() -> None:
    lines, _ = run_agent("""
        main: counter {
            beliefs { p(1). p(2). }
            program { if bel(q(X)) then print(X). }
            perceptrules { if bel(p(X)) then insert(q(X)). }
        }
    """, cycles=1)
    assert lines == ["1"]


def test_goal_3_nested_modules_are_entered_when_their_context_holds() -> None:
    # GOAL 3's misc/deliveryAgent.goal: module deliver_order { context[focusmethod=filter]
    # { goal(..) } goals {..} program {..} } inside the program
    lines, _ = run_agent("""
        main: delivery {
            beliefs { at(a). }
            goals { delivered(c1). }
            program {
                module deliver{
                    context[focusmethod=filter]{ goal(delivered(C)) }
                    program {
                        if goal(delivered(C)), bel(at(a)) then go(b) + print(go(C)).
                        if goal(delivered(C)), bel(at(b)) then insert(delivered(C))
                            + print(delivered(C)).
                    }
                }
            }
            actionspec { go(Y) { pre { at(X) } post { not(at(X)), at(Y) } } }
        }
    """, cycles=4)
    assert lines == ["go(c1)", "delivered(c1)"]


def test_an_identifier_may_start_with_a_keyword(tmp_path) -> None:
    # GOAL 5 masTest: a test named testPrinted10x was split into `test` + `Printed10x`
    (tmp_path / "a.goal").write_text("main module { program { if true then print(x). } }")
    (tmp_path / "a.mas2g").write_text('agentfiles { "a.goal". } launchpolicy { launch a. }')
    test = parse_test(textwrap.dedent("""
        masTest {
            mas = "a.mas2g".
            a { testPrinted10x { do main. } }
        }
    """), str(tmp_path / "a.test2g"))
    assert [step.target for step in test.agent_tests[0].steps] == ["main"]
    program = parse_agent("main module { program { if bel(notice, ifx, do_it) then "
                          "print(x). } }", "k.goal")
    assert program.module("main").rules[0].condition[0].query.text == "notice, ifx, do_it"


def test_backslashes_in_mas2g_strings_are_verbatim_as_goal_reads_them() -> None:
    mas = parse_mas(textwrap.dedent(r"""
        environment {
            env = "C:\Users\me\x.jar".
            init = [path = "C:\Starcraft\units", quote = "a\"b"].
        }
        agentfiles { "a.goal". }
        launchpolicy { launch a. }
    """), "w.mas2g")
    values = {key: get_engine().parse_term(value.text) for key, value in mas.env_init}
    assert mas.environment == "C:/Users/me/x.jar"
    assert values == {"path": "C:\\Starcraft\\units", "quote": 'a"b'}


def test_a_wildcard_in_use_names_every_matching_file(tmp_path) -> None:
    (tmp_path / "util").mkdir()
    (tmp_path / "util" / "a.pl").write_text("a(1).")
    (tmp_path / "util" / "b.pl").write_text("b(2).")
    (tmp_path / "main.mod2g").write_text(
        "use 'util/*.pl' as knowledge.\n"
        "module main { if bel(a(X), b(Y)) then print(X-Y). }")
    (tmp_path / "s.mas2g").write_text(
        'define ag as agent { use main as main module. }\nlaunchpolicy { launch ag. }')
    program = load_agents(parse_mas_file(tmp_path / "s.mas2g"))["ag"]
    assert [k.text for k in program.knowledge] == ["a(1)", "b(2)"]
    (tmp_path / "main.mod2g").write_text("use 'none/*.pl' as knowledge.\n"
                                         "module main { if true then print(x). }")
    with pytest.raises(GoalSyntaxError, match=r"main.mod2g:1:1: use none/\*.pl: no file "
                       "matches"):
        load_agents(parse_mas_file(tmp_path / "s.mas2g"))


def test_latin1_text_and_swi7_infix_bar_in_arguments(tmp_path) -> None:
    path = tmp_path / "l.goal"
    path.write_bytes(b"% r\xe9sum\xe9\nmain module [exit=always] {\n"
                     b"  program { if bel(X = 1) then print(\"a:\"|X). }\n}\n")
    agent = Agent(parse_agent_file(path), output=io.StringIO(), warn=lambda message: None)
    try:
        agent.run(max_cycles=1)
        assert agent.output.getvalue() == '"a:"|1\n'
    finally:
        agent.close()
