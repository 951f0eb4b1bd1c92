"""The mental state on SWI-Prolog: the MSC table and the actions table (fixtures in
conftest.py; errors and isolation in test_kb_mentalstate_isolation.py)."""

from __future__ import annotations

import pytest

from goalagent.kb import KBError, MentalState, PrologRuntimeError, Struct, Var

from .states import a, lit, neg, on, text, values

# --------------------------------------------------------------------------- MSC table


def test_bel_uses_knowledge_and_beliefs(blocks: MentalState) -> None:
    assert values(blocks.query("bel", "clear(X)"), "X") == [a("table"), a("b"), a("c")]
    assert blocks.query("bel", "tower([c, a])") == [{}]
    assert blocks.query("bel", "tower([a, b])") == []


def test_bel_accepts_any_prolog_query(blocks: MentalState) -> None:
    answers = blocks.query(
        "bel",
        "findall(B, block(B), Bs), length(Bs, N), member(X, Bs), \\+ on(X, table), "
        "(X == c -> Kind = top ; Kind = other), not(on(_, c)), N * 2 > 5",
    )
    assert answers == [{"B": Var(answers[0]["B"].name), "Bs": [a("a"), a("b"), a("c")],
                        "N": 3, "X": a("c"), "Kind": a("top")}]
    assert isinstance(answers[0]["B"], Var)


def test_goal_follows_from_knowledge_and_one_goal(blocks: MentalState) -> None:
    towers = values(blocks.query("goal", "tower(T)"), "T")
    assert towers == [[a("c")], [a("a"), a("b"), a("c")], [a("b"), a("c")]]
    assert blocks.query("goal", "on(a, b), on(b, c)") == [{}]


def test_goal_checks_each_goal_on_its_own(empty: MentalState) -> None:
    assert empty.adopt("on(a, b)")
    assert empty.adopt("on(b, c)")
    assert empty.query("goal", "on(a, b)") == [{}]
    assert empty.query("goal", "on(b, c)") == [{}]
    assert empty.query("goal", "on(a, b), on(b, c)") == []


def test_goal_sees_knowledge_rules_over_the_goal_facts() -> None:
    with MentalState("k", knowledge=[text("tower([X]) :- on(X, table)")]) as state:
        assert state.adopt("on(a, table)")
        assert state.query("goal", "tower([a])") == [{}]
        assert state.query("bel", "tower([a])") == []


def test_a_goal_and_goal_a(blocks: MentalState) -> None:
    todo = blocks.query("a-goal", "on(X, Y)")
    assert [(x["X"], x["Y"]) for x in todo] == [
        (a("a"), a("b")), (a("b"), a("c")), (a("c"), a("table"))]
    assert blocks.query("goal-a", "on(X, Y)") == []
    blocks.insert("not(on(c, a)), on(c, table)")
    assert values(blocks.query("goal-a", "on(X, Y)"), "X") == [a("c")]
    assert values(blocks.query("a-goal", "on(X, Y)"), "X") == [a("a"), a("b")]
    assert values(blocks.query("a-goal", "tower([X | T])"), "X") == [a("a"), a("b")]


def test_percept_and_bel_percept_see_this_cycles_percepts(empty: MentalState) -> None:
    empty.set_percepts([on("a", "b"), Struct("block", (a("a"),))])
    assert values(empty.query("percept", "on(X, b)"), "X") == [a("a")]
    assert empty.query("bel", "percept(on(a, b))") == [{}]
    assert empty.query("percept", "on(a, b), block(a)") == [{}]
    empty.set_percepts([on("c", "d")])
    assert empty.percepts() == [on("c", "d")]
    assert empty.query("percept", "on(a, b)") == []
    assert empty.beliefs() == []


def test_true_and_not(blocks: MentalState) -> None:
    assert blocks.query("true", "") == [{}]
    cond = (lit("bel", "block(X)"), neg(lit("bel", "on(_, X)")), neg(lit("goal-a", "on(X, _)")))
    assert values(blocks.solutions(blocks.compile(cond)), "X") == [a("b"), a("c")]
    blocks.insert("not(on(c, a)), on(c, table)")
    assert values(blocks.solutions(blocks.compile(cond)), "X") == [a("a"), a("b")]
    cond_true = (lit("true"),)
    assert blocks.solutions(blocks.compile(cond_true)) == [{}]


def test_a_condition_is_one_conjunction_sharing_variables(blocks: MentalState) -> None:
    cond = (lit("a-goal", "on(X, Y)"), lit("bel", "clear(X), clear(Y)"))
    compiled = blocks.compile(cond)
    assert compiled.names == ("X", "Y")
    assert blocks.solutions(compiled) == [
        {"X": a("b"), "Y": a("c")}, {"X": a("c"), "Y": a("table")}]
    blocks.delete("on(c, a)")
    blocks.insert("on(c, table)")
    assert blocks.solutions(compiled) == [{"X": a("a"), "Y": a("b")}, {"X": a("b"), "Y": a("c")}]


def test_solutions_with_bindings_limit_and_duplicates(empty: MentalState) -> None:
    empty.insert("p(1), p(2), p(3)")
    compiled = empty.compile((lit("bel", "p(X), member(Y, [x, x])"),))
    answers = empty.solutions(compiled)
    assert [(x["X"], x["Y"]) for x in answers] == [
        (1, a("x")), (1, a("x")), (2, a("x")), (2, a("x")), (3, a("x")), (3, a("x"))]
    assert empty.solutions(compiled, limit=1) == [{"X": 1, "Y": a("x")}]
    assert empty.solutions(compiled, limit=0) == []
    bound = empty.solutions(compiled, {"X": 2, "Other": "kept"})
    assert bound == [{"Other": "kept", "X": 2, "Y": a("x")}] * 2


def test_compile_is_cached_per_condition_text(empty: MentalState) -> None:
    first = empty.compile((lit("bel", "p(X)"),))
    assert empty.compile((lit("bel", "p(X)"),)) is first


def test_cut_inside_a_query_only_cuts_that_query(empty: MentalState) -> None:
    empty.insert("p(1), p(2), q(a), q(b)")
    cond = (lit("bel", "p(X)"), lit("bel", "q(Y), !"))
    assert [(x["X"], x["Y"]) for x in empty.solutions(empty.compile(cond))] == [
        (1, a("a")), (2, a("a"))]


# --------------------------------------------------------------------------- actions table


def test_insert_and_delete_with_not(empty: MentalState) -> None:
    assert empty.insert("on(a, b), on(b, table)") == [("+", on("a", "b")), ("+", on("b", "table"))]
    assert empty.insert("on(a, b)") == []
    changes = empty.insert("not(on(a, b)), on(a, table)")
    assert changes == [("-", on("a", "b")), ("+", on("a", "table"))]
    assert empty.beliefs() == [on("b", "table"), on("a", "table")]
    changes = empty.delete("on(a, table), not(holding(a))")
    assert changes == [("-", on("a", "table")), ("+", Struct("holding", (a("a"),)))]
    assert empty.delete("on(x, y)") == []


def test_updates_apply_bindings_and_report_what_changed(empty: MentalState) -> None:
    changes = empty.insert(text("at(X, Y)"), {"X": a("r1"), "Y": 3})
    assert changes == [("+", Struct("at", (a("r1"), 3)))]
    assert empty.delete("at(r1, _)") == [("-", Struct("at", (a("r1"), 3)))]


def test_insert_of_a_non_ground_fact_is_a_clear_error(empty: MentalState) -> None:
    with pytest.raises(KBError, match="not ground"):
        empty.insert("on(X, b)")
    assert empty.beliefs() == []


def test_adopt_refused_when_believed_or_already_a_goal(blocks: MentalState) -> None:
    assert not blocks.adopt("on(a, table)")
    assert not blocks.adopt("on(c, table), on(a, b), on(b, c)")
    assert blocks.adopt("on(b, c)")
    assert not blocks.adopt(text("on(X, c)"), {"X": a("b")})
    assert len(blocks.goals()) == 2


def test_adopt_needs_ground_facts(empty: MentalState) -> None:
    with pytest.raises(KBError, match="not ground"):
        empty.adopt("on(X, b)")
    assert empty.goals() == []


def test_adopt_then_goals_lists_facts(empty: MentalState) -> None:
    assert empty.adopt(text("on(X, b), on(b, c)"), {"X": a("a")})
    assert empty.goals() == [[on("a", "b"), on("b", "c")]]


def test_drop_removes_every_goal_entailing_the_formula() -> None:
    with MentalState("d", knowledge=[text("tower([X]) :- on(X, table)")]) as state:
        state.adopt("on(a, b), on(b, table)")
        state.adopt("on(c, table)")
        state.adopt("on(d, e)")
        dropped = state.drop("tower([_])")
        assert dropped == [[on("a", "b"), on("b", "table")], [on("c", "table")]]
        assert state.goals() == [[on("d", "e")]]
        assert state.drop("never(seen)") == []


def test_blind_commitment_removes_achieved_goals(blocks: MentalState) -> None:
    blocks.adopt("on(a, table)")  # refused: already believed
    blocks.adopt("holding(c)")
    assert blocks.blind_commitment() == []
    blocks.insert("not(on(c, a)), on(c, table), on(b, c), on(a, b)")
    assert blocks.blind_commitment() == [[on("a", "b"), on("b", "c"), on("c", "table")]]
    assert blocks.goals() == [[Struct("holding", (a("c"),))]]


def test_blind_commitment_uses_knowledge() -> None:
    with MentalState("k", knowledge=[text("done(X) :- finished(X)")]) as state:
        state.declare_updates(["finished(job)"])
        assert state.adopt("done(job)")
        state.insert("finished(job)")
        assert state.blind_commitment() == [[Struct("done", (a("job"),))]]


def test_goal_bases_for_module_focus(blocks: MentalState) -> None:
    outer = blocks.goals()
    blocks.push_goal_base([[on("x", "y")]])
    assert blocks.goals() == [[on("x", "y")]]
    assert blocks.query("goal", "on(a, b)") == []
    assert blocks.adopt("on(p, q)")
    assert blocks.pop_goal_base() == [[on("x", "y")], [on("p", "q")]]
    assert blocks.goals() == outer
    with pytest.raises(KBError, match="pop_goal_base"):
        blocks.pop_goal_base()


def test_messages_received_and_sent_moods(empty: MentalState) -> None:
    empty.receive([("bob", ":", on("a", "b")), ("bob", "!", on("a", "b"))])
    empty.receive([("eve", "?", Struct("free", (a("c"),)))])
    answers = empty.query("bel", "received(S, M)")
    assert [(x["S"], x["M"]) for x in answers] == [
        (a("bob"), on("a", "b")),
        (a("bob"), Struct("imp", (on("a", "b"),))),
        (a("eve"), Struct("int", (Struct("free", (a("c"),)),))),
    ]
    empty.receive([("eve", ":", on("c", "d"))], replace=True)  # GOAL 6+: one cycle's mail
    assert empty.query("bel", "received(S, M)") == [{"S": a("eve"), "M": on("c", "d")}]
    empty.receive([], replace=True)
    assert empty.query("bel", "received(S, M)") == []
    assert empty.add_sent("bob", "!", on("a", "b"))
    assert not empty.add_sent("bob", "!", on("a", "b"))
    assert empty.query("bel", "sent(bob, imp(on(a, b)))") == [{}]
    with pytest.raises(KBError, match="mood"):
        empty.add_sent("bob", "#", on("a", "b"))


def test_identity(empty: MentalState) -> None:
    empty.set_identity("alice", ["alice", "bob"])
    assert empty.query("bel", "me(Me)") == [{"Me": a("alice")}]
    assert values(empty.query("bel", "agent(A)"), "A") == [a("alice"), a("bob")]
    empty.set_identity("alice", ["alice"])
    assert values(empty.query("bel", "agent(A)"), "A") == [a("alice")]


def test_agents_of_a_directory_share_one_agent_list(empty: MentalState) -> None:
    from goalagent.kb.identity import AgentDirectory

    directory = AgentDirectory()
    with MentalState("other") as other:
        directory.add("alice")
        empty.join("alice", directory)
        other.join("bob", directory)
        directory.add("bob")  # added after bob joined: both see it
        for state, me in ((empty, "alice"), (other, "bob")):
            assert state.query("bel", "me(Me)") == [{"Me": a(me)}]
            assert values(state.query("bel", "agent(A)"), "A") == [a("alice"), a("bob")]
        assert empty.beliefs() == [Struct("me", (a("alice"),))]  # the list is not copied
    directory.close()
    with pytest.raises(KBError, match="closed"):
        directory.add("carol")
    with pytest.raises(KBError, match="closed"):
        empty.join("alice", directory)


def test_vocabulary_is_always_queryable(empty: MentalState) -> None:
    for query in ["percept(X)", "received(S, M)", "sent(R, M)", "me(X)", "agent(X)"]:
        assert empty.query("bel", query) == []
        assert empty.query("goal", query) == []


def test_beliefs_exclude_knowledge_and_percepts(blocks: MentalState) -> None:
    blocks.set_percepts([a("ping")])
    assert blocks.beliefs() == [on("a", "table"), on("b", "table"), on("c", "a")]


def test_belief_rules_and_directives_are_loaded() -> None:
    with MentalState(
        "r",
        knowledge=[text(":- dynamic holding/1"), text("heavy(X) :- weight(X, W), W > 10")],
        beliefs=[text("weight(box, 12)"), text("light(X) :- weight(X, W), W < 5")],
    ) as state:
        assert state.query("bel", "holding(X)") == []
        assert state.query("goal", "holding(X)") == []
        assert state.query("bel", "heavy(box)") == [{}]
        assert state.query("bel", "light(box)") == []
        assert state.beliefs() == [Struct("weight", (a("box"), 12))]


def test_declare_updates_makes_predicates_queryable(empty: MentalState) -> None:
    with pytest.raises(PrologRuntimeError, match="Unknown procedure: holding/1"):
        empty.query("bel", "holding(X)")
    empty.declare_updates([text("not(on(X, Y)), holding(X)"), "at(r, 1)"])
    for op in ["bel", "goal", "a-goal", "goal-a"]:
        assert empty.query(op, "holding(X), on(X, Y)") == []
        assert empty.query(op, "at(_, _)") == []


def test_instantiate_and_unify(empty: MentalState) -> None:
    term = empty.instantiate(text("move(X, Y, [X | T])"), {"X": a("a")})
    assert term == Struct("move", (a("a"), Var("Y"), Struct("[|]", (a("a"), Var("T")))))
    assert empty.unify("move(X, Y)", Struct("move", (a("a"), [1, 2]))) == {
        "X": a("a"), "Y": [1, 2]}
    assert empty.unify("move(X, X)", Struct("move", (a("a"), a("b")))) is None
    assert empty.unify("move(X, Y)", Struct("move", (a("a"), a("b"))), {"X": a("b")}) is None
    assert empty.unify("move(X, Y)", Struct("move", (a("a"), a("b"))), {"Z": 1}) == {
        "Z": 1, "X": a("a"), "Y": a("b")}
    assert empty.unify("f([H | T])", Struct("f", ([1, 2, 3],))) == {"H": 1, "T": [2, 3]}
    assert empty.unify("n(1)", Struct("n", (1.0,))) is None
    assert empty.unify("s(abc)", Struct("s", ("abc",))) is None
