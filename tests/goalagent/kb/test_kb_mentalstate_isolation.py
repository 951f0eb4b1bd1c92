"""The mental state on SWI-Prolog: errors (located, the state still usable after them) and
isolation (agents never see each other, nothing leaks into or out of ``user``)."""

from __future__ import annotations

import pytest

from goalagent import ast
from goalagent.kb import Atom, KBError, MentalState, PrologRuntimeError, Struct, get_engine

from .states import POS, a, lit, on, text, values

# --------------------------------------------------------------------------- errors


def test_unknown_procedure_and_type_error_then_state_still_works(blocks: MentalState) -> None:
    with pytest.raises(PrologRuntimeError) as info:
        blocks.query("bel", "no_such_thing(X)")
    assert info.value.message == "Unknown procedure: no_such_thing/1"
    with pytest.raises(PrologRuntimeError, match="Type error"):
        blocks.query("bel", "block(X), atom_length(X, foo)")
    with pytest.raises(PrologRuntimeError, match="Arithmetic"):
        blocks.query("goal", "on(X, _), Y is X + 1")
    with pytest.raises(PrologRuntimeError, match="Unknown procedure: nope/0"):
        blocks.query("goal", "nope")
    assert values(blocks.query("bel", "clear(X)"), "X") == [a("table"), a("b"), a("c")]
    assert blocks.insert("on(b, c)") == [("+", on("b", "c"))]


def test_error_inside_an_update_is_a_kb_error(empty: MentalState) -> None:
    with pytest.raises(KBError, match="atom/1 is a built-in predicate of ISO Prolog"):
        empty.insert("atom(x)")
    assert empty.insert("ok(1)") == [("+", Struct("ok", (1,)))]


def test_bad_clause_names_the_clause_and_position() -> None:
    bad = ast.Pos("agent.goal", 7, 9, 120)
    with pytest.raises(KBError) as info:
        MentalState("bad", knowledge=[text("ok(1)"), text("atom(X) :- true", bad)])
    assert "atom(X) :- true" in info.value.message
    assert info.value.pos == bad
    with pytest.raises(KBError) as info:
        MentalState("bad", beliefs=[text("p(")])
    assert "p(" in info.value.message and "syntax error" in info.value.message
    assert info.value.pos == POS
    with pytest.raises(KBError, match="directive failed"):
        MentalState("bad", knowledge=[text(":- fail")])


def test_condition_syntax_error_names_the_literal() -> None:
    with MentalState("c") as state:
        where = ast.Pos("agent.goal", 12, 3, 200)
        literal = ast.MentalLiteral("bel", text("p(X", where), where)
        with pytest.raises(KBError) as info:
            state.compile((lit("bel", "true"), literal))
        assert info.value.pos == where
        with pytest.raises(KBError, match="unknown mental literal"):
            state.query("believe", "p")


def test_closed_state_is_unusable() -> None:
    state = MentalState("gone")
    compiled = state.compile((lit("bel", "true"),))
    state.close()
    state.close()
    with pytest.raises(KBError, match="closed"):
        state.query("bel", "true")
    with pytest.raises(KBError, match="closed"):
        state.solutions(compiled)


def test_condition_of_another_state_is_rejected(empty: MentalState) -> None:
    with MentalState("other") as other:
        compiled = other.compile((lit("bel", "true"),))
        with pytest.raises(KBError, match="another mental state"):
            empty.solutions(compiled)


# --------------------------------------------------------------------------- isolation


def test_agents_never_see_each_other() -> None:
    with MentalState("twin", knowledge=[text("k(1)")]) as one, \
            MentalState("twin", knowledge=[text("k(2)")]) as two:
        one.insert("on(a, b)")
        one.adopt("on(x, y)")
        one.set_percepts([a("seen")])
        two.declare_updates(["on(a, b)"])
        assert two.query("bel", "on(X, Y)") == []
        assert two.query("goal", "on(X, Y)") == []
        assert two.query("bel", "percept(X)") == []
        assert values(two.query("bel", "k(X)"), "X") == [2]
        assert values(one.query("bel", "k(X)"), "X") == [1]
        assert two.goals() == [] and two.beliefs() == []


def test_nothing_leaks_into_user_and_user_does_not_leak_in(empty: MentalState) -> None:
    engine = get_engine()
    empty.insert("leak_probe(1)")
    assert engine.call("current_predicate", Struct("/", (a("leak_probe"), 1)),
                       module="user") is None
    engine.call("assertz", Struct("user_only", (1,)), module="user")
    with pytest.raises(PrologRuntimeError, match="Unknown procedure"):
        empty.query("bel", "user_only(X)")


def test_library_predicates_are_available(empty: MentalState) -> None:
    answers = empty.query("bel", "last([1, 2, 3], X), sum_list([1, 2], S), msort([b, a], L)")
    assert answers == [{"X": 3, "S": 3, "L": [a("a"), a("b")]}]


def test_close_frees_the_modules() -> None:
    engine = get_engine()
    state = MentalState("tmp")
    state.insert("p(1)")
    module = state._b
    assert engine.call("current_module", module, module="system") is not None
    state.close()
    assert engine.call("current_module", module, module="system") is None


def test_beliefs_order_is_deterministic(empty: MentalState) -> None:
    empty.insert("zeta(1), alpha(2), zeta(0), alpha(1)")
    assert empty.beliefs() == [
        Struct("alpha", (2,)), Struct("alpha", (1,)), Struct("zeta", (1,)), Struct("zeta", (0,))]


def test_operator_and_library_directives_stay_in_the_agent() -> None:
    knowledge = [
        text(":- use_module(library(clpfd))"),
        text("sum3(X, Y, Z) :- Z #= X + Y"),
        text(":- op(700, xfx, ===>)"),
        text("rule(a ===> b)"),
    ]
    with MentalState("ops", knowledge=knowledge) as state, MentalState("plain") as plain:
        assert state.query("bel", "sum3(1, 2, Z)") == [{"Z": 3}]
        assert state.query("bel", "rule(X ===> Y)") == [{"X": a("a"), "Y": a("b")}]
        assert state.adopt("wanted(3)")
        assert state.query("goal", "wanted(W), sum3(1, 2, W)") == [{"W": 3}]
        with pytest.raises(KBError, match="Operator expected"):
            plain.query("bel", "X = (a ===> b)")
        with pytest.raises(KBError, match="Operator expected"):
            get_engine().check_query("X = (a ===> b)")


def test_comments_in_queries_and_cyclic_answers(empty: MentalState) -> None:
    assert empty.query("bel", "X = 1 % the answer") == [{"X": 1}]
    with pytest.raises(KBError, match="cyclic"):
        empty.query("bel", "X = f(X)")
    assert empty.query("bel", "true") == [{}]


def test_agent_modules_read_text_like_swi(empty: MentalState) -> None:
    answers = empty.query("bel", "X = \"abc\", Y = `ab`, Z = 0'c, W = {a}, V = 'it''s'")
    assert answers == [{"X": "abc", "Y": [97, 98], "Z": 99,
                        "W": Struct("{}", (a("a"),)), "V": a("it's")}]
    assert not isinstance(answers[0]["X"], Atom)
    empty.insert('note("hello world")')
    assert empty.beliefs() == [Struct("note", ("hello world",))]


def test_updates_remove_achieved_goals_at_once_and_report_them_once(empty: MentalState) -> None:
    assert empty.adopt("at(home)")
    assert empty.adopt("rich")
    empty.insert("at(home)")
    assert empty.goals() == [[a("rich")]]
    assert empty.blind_commitment() == [[Struct("at", (a("home"),))]]
    assert empty.blind_commitment() == []
    with MentalState("k", knowledge=[text("happy :- percept(sunny)")]) as other:
        assert other.adopt("happy")
        other.set_percepts([a("sunny")])
        assert other.goals() == [[a("happy")]]
        assert other.blind_commitment() == [[a("happy")]]
        assert other.goals() == []


def test_instantiate_returns_fresh_terms(empty: MentalState) -> None:
    first = empty.instantiate("[a, [b]]", {})
    assert isinstance(first, list)
    first.append(a("c"))
    assert empty.instantiate("[a, [b]]", {}) == [a("a"), [a("b")]]


def test_update_reports_every_removed_copy_and_checks_before_changing() -> None:
    with MentalState("dup", beliefs=[text("p(1)"), text("p(1)"), text("q(2)")]) as state:
        assert state.delete("p(1), q(_), r(9)") == [
            ("-", Struct("p", (1,))), ("-", Struct("p", (1,))), ("-", Struct("q", (2,)))]
        state.insert("s(1)")
        with pytest.raises(KBError, match="not ground"):
            state.insert("not(s(1)), t(X)")
        assert state.beliefs() == [Struct("s", (1,))]
        assert state.insert("true, not(s(1)), (u(1), u(2)), true") == [
            ("-", Struct("s", (1,))), ("+", Struct("u", (1,))), ("+", Struct("u", (2,)))]
