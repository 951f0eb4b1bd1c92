"""What the compiled clauses write inline (issue 29 item 3).

An agent's conditions and knowledge run their arithmetic inline (ga_sizes:inline_clause/2):
the same answers and the same warnings, word for word, as when each comparison and is/2 was
a call of the built-in, for the first agent of a program and for the agents that copy its
clauses; an unknown function is still a warning when the rule runs, not an error when the
agent loads. A rule's insert or delete of one fact tests its variables inline and calls
the update for a ground fact (rules.pl's ground_code/4): facts whose variables hold
compounds, or nothing, are inserted, deleted and refused as before, traced or not.
"""

from __future__ import annotations

import io
import re

from goalagent.agent import Agent
from goalagent.ast import AgentProgram
from goalagent.kb.engine import get_engine
from goalagent.kb.terms import Atom, Struct, Term, Var
from goalagent.parser import parse_agent

PROGRAM = """
init module { knowledge {
    half(X, Y) :- Y is X / 2.
    big(X) :- X > 10.
    calc(X, Y) :- Y is foo(X) + 1.
    sq(X, Y) :- Y is X * X. twice(X, Y) :- Y is X * 2.
} beliefs { v(a). w(0). e(1+2). s("ab"). f(1.0e308). } }
main module [exit=always] { program [order=linearall] {
    if bel(v(X), Y is X + 1) then print(Y).
    if bel(v(X), X > 1) then print(X).
    if bel(w(X), Y is 1 / X) then print(Y).
    if bel(w(X), Y is X mod 0) then print(Y).
    if bel(Z > 1) then print(Z).
    if bel(v(X), half(X, Y)) then print(Y).
    if bel(v(X), big(X)) then print(X).
    if bel(w(X), calc(X, Y)) then print(Y).
    if bel(w(X), Y is bar(X)) then print(Y).
    if bel(e(E), Y is E * 2) then print(Y).
    if bel(e(E), E > 2) then print(E).
    if bel(s(S), Y is S + 1) then print(Y).
    if bel(w(X), Y is X + 2.5, Y >= 2.5, sq(3, Q), Q =:= 9, 3 =\\= Q) then print(Y).
    if bel(w(X), X < 1.0e300 * 1.0e300) then print(X).
    if bel(f(F), Y is F * 10) then print(Y).
    if bel(f(F), twice(F, Y)) then print(Y).
    if bel(w(X), Y is 7 / (X + 2), Z is -7 // (X + 2), M is -7 mod (X + 2)) then print(Y/Z/M).
} }
"""

# What each rule said when every arithmetic goal was a call of the built-in (main at
# b48d174 printed these, rule by rule).
CONDITION_ERRORS = {
    9: "is/2: Arithmetic: `a/0' is not a function",
    10: ">/2: Arithmetic: `a/0' is not a function",
    11: "//2: Arithmetic: evaluation error: `zero_divisor'",
    12: "mod/2: Arithmetic: evaluation error: `zero_divisor'",
    13: ">/2: Arguments are not sufficiently instantiated",
    14: "is/2: Arithmetic: `a/0' is not a function",
    15: ">/2: Arithmetic: `a/0' is not a function",
    16: "is/2: Arithmetic: `foo/1' is not a function",
    17: "is/2: Arithmetic: `bar/1' is not a function",
    20: "is/2: Type error: `[]' expected, found `\"ab\"' (a string) "
        "(\"x\" must hold one character)",
    22: "Arithmetic: evaluation error: `float_overflow'",
    # a float's overflow in a condition and in knowledge: inline it would lose its `is/2'
    23: "is/2: Arithmetic: evaluation error: `float_overflow'",
    24: "is/2: Arithmetic: evaluation error: `float_overflow'",
}


def _cycles(program: AgentProgram, names: list[str]) -> list[tuple[list[str], list[str]]]:
    """One cycle of each of fresh agents of ``program`` (alive together, so that the later
    ones copy the first one's clauses): their warnings and what they printed."""
    outputs = {name: io.StringIO() for name in names}
    warnings: dict[str, list[str]] = {name: [] for name in names}
    agents = [Agent(program, name=name, output=outputs[name], warn=warnings[name].append)
              for name in names]
    try:
        for agent in agents:
            agent.step()
    finally:
        for agent in agents:
            agent.close()
    return [(warnings[name], outputs[name].getvalue().split()) for name in names]


def test_arithmetic_answers_and_errors_as_the_built_ins_give_them():
    program = parse_agent(PROGRAM, "m.goal")
    for name, (warnings, printed) in zip(["first", "copy"], _cycles(program, ["first", "copy"]),
                                         strict=True):
        assert warnings == [
            f"warning: agent {name}: module main, rule at m.goal:{line}:5: Prolog error in "
            f"the condition: {message}; the rule is not applicable"
            for line, message in CONDITION_ERRORS.items()]
        assert printed == ["6", "1+2", "2.5", "3.5/", "-3/1"]  # (print writes 3.5/ -3/1)


def _printed(goal: Term) -> str:
    """What ``goal`` prints."""
    answer = get_engine().call("with_output_to", Struct("string", (Var("S"),)), goal,
                               module="user", read=[0])
    assert answer is not None and isinstance(answer[0], Struct)
    return str(answer[0].args[0])


def _inline(clause: str) -> str:
    """The clause written in Prolog, as inline_clause/2 makes it (printed)."""
    return _printed(Struct(",", (
        Struct("term_string", (Var("C"), clause)),
        Struct(",", (Struct(":", (Atom("ga_sizes"), Struct("inline_clause", (Var("C"),
                                                                             Var("I"))))),
                     Struct("\\+", (Struct("\\+", (Struct(",", (
                         Struct("numbervars", (Var("I"), 0, Var("_"))),
                         Struct("print", (Var("I"),)))),)),)))))))


def test_inline_clause_guards_what_can_run_inline_and_calls_the_rest():
    # integer arithmetic inline after integer/1; bare numbers compared after number/1
    assert _inline("h(X, Y) :- Y is X + 1, Y > 2") == (
        "h(A,B):-(integer(A)->B is A+1;ga_sizes:evaluated(B is A+1)),"
        "(number(B)->B>2;ga_sizes:evaluated(B>2))")
    # no variable, a function not inline, a power (checked step by step), a string, a
    # float or a division to a float (their overflow is worded with is/2 by the built-in)
    for goal in ("Y is 1 + 2", "Y is foo(X)", "Y > X ** 2", "Y is X + \"a\"", "Y is pi",
                 "Y is X * 2.5", "Y is X / 2"):
        inlined = _inline(f"h(X, Y) :- {goal}")
        assert "number(" not in inlined and "ga_sizes:evaluated(" in inlined, goal
    # through control constructs; a guard made already (sized/3, or here) is kept as it is
    assert _inline("h(X) :- \\+ (X > 1 ; X < 0 -> true ; (number(X) -> X =:= 1 "
                   "; ga_sizes:evaluated(X =:= 1)))") == (
        "h(A):- \\+ ((number(A)->A>1;ga_sizes:evaluated(A>1));"
        "(number(A)->A<0;ga_sizes:evaluated(A<0))->true;"
        "number(A)->A=:=1;ga_sizes:evaluated(A=:=1))")


def _vm_code(module: Atom) -> str:
    """The virtual-machine code of an agent's knowledge half/2 and big/1 and of its
    conditions ('$ga_c...'), as vm_list/1 prints it."""
    predicate = Struct(":", (module, Struct("/", (Var("P"), Var("_")))))
    wanted = Struct(";", (Struct("memberchk", (Var("P"), [Atom("half"), Atom("big")])),
                          Struct("sub_atom", (Var("P"), 0, Var("_"), Var("_"),
                                              Atom("$ga_c")))))
    return _printed(Struct("forall", (Struct(",", (Struct("current_predicate", (predicate,)),
                                                   wanted)),
                                       Struct("vm_list", (Struct(":", (module, Var("P"))),)))))


def test_conditions_and_knowledge_are_compiled_inline_in_every_agent_of_a_program():
    program = parse_agent(PROGRAM, "m.goal")
    agents = [Agent(program, name=name, output=io.StringIO(), warn=lambda _: None)
              for name in ("first", "copy")]  # the copy copies the first's clauses
    try:
        for agent in agents:
            code = _vm_code(Atom(str(agent._rules._code._state._b)))  # (inside the agent)
            assert "a_is" in code and "a_gt" in code and "a_ge" in code
            assert "system:(is)/2" not in code and "system:(>)/2" not in code
    finally:
        for agent in agents:
            agent.close()
    assert get_engine().call("current_prolog_flag", Atom("optimise"), Atom("false"),
                             module="user") is not None


UPDATES = """
init module { beliefs { r(_). cell(pos(1, 2)). cell(pos(3, 4)). n(1). } }
main module [exit=always] { program [order=linearall] {
    forall bel(cell(P)) do insert(at(P)).
    if bel(cell(pos(1, 2))) then delete(cell(pos(1, 2))) + insert(moved(pos(1, 2), [a, "b"])).
    if bel(r(X)) then insert(q(X)).
    if bel(n(N)) then delete(n(N)) + insert(n(f(N))).
    if bel(n(f(N))) then delete(n(f(N))).
} }
"""


def _updates(traced: bool) -> tuple[list[str], list[str]]:
    """Two cycles of UPDATES: the beliefs after, and the warnings."""
    warnings: list[str] = []
    agent = Agent(parse_agent(UPDATES, "u.goal"), name="u", output=io.StringIO(),
                  warn=warnings.append,
                  tracer=(lambda agent, kind, text: None) if traced else None)
    try:
        agent.run(2)
        beliefs = sorted(re.sub(r"_G\d+", "_", str(belief)) for belief in agent.beliefs())
    finally:
        agent.close()
    return beliefs, warnings


def test_updates_of_facts_whose_variables_hold_compounds_or_nothing():
    beliefs, warnings = _updates(traced=False)
    assert beliefs == ["at(pos(1,2))", "at(pos(3,4))", "cell(pos(3,4))",
                       "moved(pos(1,2),[a,\"b\"])", "r(_)"]
    assert warnings == ["warning: agent u: u.goal:6:23: insert failed: insert: q(_) is not "
                        "ground (unbound variables)"]  # (told once)
    assert _updates(traced=True) == (beliefs, warnings)


RULE_BESIDE_FACT = """
init module { beliefs { f(1). f(X) :- g(X). g(2). } }
main module [exit=always] { program [order=linearall] {
    if bel(f(1)) then delete(f(1)).
} }
"""


def test_deleting_a_fact_leaves_the_belief_rules_whose_head_unifies_with_it():
    # untraced, the delete took the rule f(X) :- g(X) too (retractall/1); traced it did not
    for traced in (False, True):
        agent = Agent(parse_agent(RULE_BESIDE_FACT, "r.goal"), name="r", output=io.StringIO(),
                      tracer=(lambda agent, kind, text: None) if traced else None)
        try:
            agent.run(1)
            assert [answer["X"] for answer in agent.query("bel", "f(X)")] == [2], traced
        finally:
            agent.close()
