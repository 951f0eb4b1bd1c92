"""Parser tests: the rules, macros and actions of the language contract (mental-state
operators, nesting, forall/listall, macro expansion, built-in and user actions, messaging,
actionspecs). ``test_parser.py`` covers the file layout and the options.
"""

from __future__ import annotations

import pytest

from goalagent import ast
from goalagent.parser import parse_agent

from .shapes import literal_ops, main_rules, one_rule, squash

# ----------------------------------------------------------------------------- rules


def test_rules_keep_program_order_and_positions() -> None:
    text = """main module {
    program {
        if bel(a) then print(1).
        forall bel(b(X)) do print(X).
        listall L <- bel(c(X)) do print(L).
        if bel(d) then { if true then print(4). }
        if true then print(5).
    }
}"""
    rules = main_rules(parse_agent(text, "order.goal"))
    assert [r.kind for r in rules] == ["if", "forall", "listall", "if", "if"]
    assert [r.pos.line for r in rules] == [3, 4, 5, 6, 7]
    assert all(r.pos.col == 9 and r.pos.file == "order.goal" for r in rules)


def test_every_mental_state_operator_in_order() -> None:
    rule = one_rule(
        "if bel(a), goal(b), a-goal(c), goal-a(d), percept(e), true, not(bel(f)) then print(x)."
    )
    assert literal_ops(rule.condition) == ["bel", "goal", "a-goal", "goal-a", "percept", "true",
                                           "not"]
    texts = [lit.query.text for lit in rule.condition[:5] if isinstance(lit, ast.MentalLiteral)
             and lit.query is not None]
    assert texts == ["a", "b", "c", "d", "e"]
    negated = rule.condition[-1]
    assert isinstance(negated, ast.NotLiteral)
    assert literal_ops(negated.condition) == ["bel"]


def test_not_of_a_conjunction_and_nested_not() -> None:
    rule = one_rule("if not(bel(a), goal(b)), not(not(a-goal(c))) then print(x).")
    first, second = rule.condition
    assert isinstance(first, ast.NotLiteral) and literal_ops(first.condition) == ["bel", "goal"]
    assert isinstance(second, ast.NotLiteral)
    inner = second.condition[0]
    assert isinstance(inner, ast.NotLiteral) and literal_ops(inner.condition) == ["a-goal"]


def test_keywords_inside_prolog_text_stay_prolog() -> None:
    rule = one_rule(
        "if bel(status(goal, then), if(not), X = a-goal, true), goal(bel(percept)) then print(X)."
    )
    assert [lit.query.text for lit in rule.condition if isinstance(lit, ast.MentalLiteral)
            and lit.query is not None] == [
        "status(goal, then), if(not), X = a-goal, true",
        "bel(percept)",
    ]


def test_table_is_a_plain_atom_as_in_classic_blocks_world_code() -> None:
    """SWI-Prolog 9 makes ``table`` a prefix operator; GOAL programs use it as an atom."""
    rule = one_rule("if bel(on(X, Y), Y \\= table, X == table ; true) then move(X, table).")
    literal = rule.condition[0]
    assert isinstance(literal, ast.MentalLiteral) and literal.query is not None
    assert literal.query.text == "on(X, Y), Y \\= table, X == table ; true"


def test_query_variables_are_recorded_in_order() -> None:
    rule = one_rule("if bel(on(X, Y), Y \\= X, tower([Y | T])) then print(T).")
    literal = rule.condition[0]
    assert isinstance(literal, ast.MentalLiteral) and literal.query is not None
    assert literal.query.variables == ("X", "Y", "T")


def test_nested_rules_two_levels_deep() -> None:
    rule = one_rule(
        """
        if bel(parcel(P, Kg)) then {
            if bel(Kg > 10) then {
                if bel(truck(T)) then insert(loaded(P, T)).
                if true then insert(waiting(P)).
            }
            forall bel(label(P, L)) do print(L).
            if true then insert(loaded(P, van)).
        }
        """
    )
    assert rule.actions == () and rule.rules is not None
    assert [r.kind for r in rule.rules] == ["if", "forall", "if"]
    inner = rule.rules[0]
    assert inner.rules is not None and len(inner.rules) == 2
    assert inner.rules[0].actions[0].name == "insert"


def test_forall_and_listall_with_nested_blocks() -> None:
    rules = main_rules(
        parse_agent(
            """
            main module { program {
                forall bel(p(X)) do { if bel(q(X)) then print(X). }
                listall Xs <- bel(p(X)) do { if bel(length(Xs, N)) then print(N). }
            } }
            """
        )
    )
    assert [(r.kind, r.list_var) for r in rules] == [("forall", None), ("listall", "Xs")]
    assert all(r.rules is not None and len(r.rules) == 1 for r in rules)


def test_listall_rule() -> None:
    rule = one_rule("listall Rooms <- goal(in(_, _, R)), bel(room(R)) do insert(rooms(Rooms)).")
    assert (rule.kind, rule.list_var) == ("listall", "Rooms")
    assert literal_ops(rule.condition) == ["goal", "bel"]
    assert rule.actions[0].name == "insert"


def test_listall_written_left_to_right() -> None:
    """GOAL 5's grammar also allows ``listall MSC -> Var do ...``."""
    rule = one_rule("listall bel(room(R)) -> Rooms do insert(rooms(Rooms)).")
    assert (rule.kind, rule.list_var, literal_ops(rule.condition)) == ("listall", "Rooms", ["bel"])


# ----------------------------------------------------------------------------- macros


def test_macro_is_expanded_where_it_is_used() -> None:
    program = parse_agent(
        """
        main module { program {
            #define ready(X) bel(item(X), clean(X)).
            if ready(cup), bel(free) then print(cup).
        } }
        """
    )
    assert [(m.name, m.params) for m in program.macros] == [("ready", ("X",))]
    rule = main_rules(program)[0]
    assert literal_ops(rule.condition) == ["bel", "bel"]
    first = rule.condition[0]
    assert isinstance(first, ast.MentalLiteral) and first.query is not None
    assert squash(first.query.text) == "item(cup),clean(cup)"


def test_macro_parameters_share_the_rule_variables() -> None:
    rule = one_rule(
        "#define constructiveMove(X, Y) a-goal(tower([X, Y | T])), bel(tower([Y | T])). "
        "if constructiveMove(A, B) then move(A, B)."
    )
    assert literal_ops(rule.condition) == ["a-goal", "bel"]
    agoal, bel = rule.condition
    assert isinstance(agoal, ast.MentalLiteral) and agoal.query is not None
    assert isinstance(bel, ast.MentalLiteral) and bel.query is not None
    assert agoal.query.variables[:2] == ("A", "B")
    # The macro's own variable T is one variable shared by both literals.
    local = [v for v in agoal.query.variables if v not in ("A", "B")]
    assert len(local) == 1 and local[0] in bel.query.variables


def test_macros_without_parameters_inside_not_and_in_forall() -> None:
    rules = main_rules(
        parse_agent(
            """
            main module { program {
                #define boxReady bel(box(_)).
                #define fresh(F, D) bel(fruit(F, D), D < 3).
                if not(boxReady) then insert(box([])).
                forall fresh(F, D) do insert(kept(F, D)).
            } }
            """
        )
    )
    negated = rules[0].condition[0]
    assert isinstance(negated, ast.NotLiteral) and literal_ops(negated.condition) == ["bel"]
    assert rules[1].kind == "forall" and literal_ops(rules[1].condition) == ["bel"]


# ----------------------------------------------------------------------------- actions


def test_action_combo_of_every_builtin() -> None:
    rule = one_rule(
        "if true then insert(p) + delete(q) + adopt(r) + drop(s) + print(t) + log(u) "
        "+ exit-module."
    )
    assert [a.name for a in rule.actions] == [
        "insert", "delete", "adopt", "drop", "print", "log", "exit-module",
    ]
    assert rule.actions[-1].args == ()


def test_user_actions_with_and_without_arguments() -> None:
    rule = one_rule("if true then pickUp + move(a, table) + nil.")
    assert [(a.name, a.arity) for a in rule.actions] == [("pickUp", 0), ("move", 2), ("nil", 0)]


def test_insert_of_not_and_conjunction() -> None:
    rule = one_rule("if bel(at(Old)) then insert((not(at(Old)), at(home))) + delete(at(Old)).")
    insert = rule.actions[0]
    assert isinstance(insert, ast.ActionCall)
    assert [squash(a.text) for a in insert.args] == ["(not(at(Old)),at(home))"]


@pytest.mark.parametrize(
    ("action", "once", "receiver", "mood", "content"),
    [
        ("allother.send(:in(r1))", False, "allother", ":", "in(r1)"),
        ("all.sendonce(!have(x))", True, "all", "!", "have(x)"),
        ("bob.send(?canMake(_, _))", False, "bob", "?", "canMake(_, _)"),
        ("Asker.sendonce(:canMake(me, [a]))", True, "Asker", ":", "canMake(me, [a])"),
        ("allother.send(not(block(b)))", False, "allother", ":", "not(block(b))"),
        ("allother.send(!not(holding(x)))", False, "allother", "!", "not(holding(x))"),
        ("maker.send(: have(beans))", False, "maker", ":", "have(beans)"),
    ],
)
def test_messaging_forms_and_moods(
    action: str, once: bool, receiver: str, mood: str, content: str
) -> None:
    rule = one_rule(f"if bel(me(Asker)) then {action}.")
    send = rule.actions[0]
    assert isinstance(send, ast.SendAction)
    assert (send.once, send.receiver.text, send.mood, send.content.text) == (
        once, receiver, mood, content,
    )
    assert send.name == ("sendonce" if once else "send")


def test_variable_addressee_in_parentheses() -> None:
    """GOAL 5 programs write a variable addressee as ``(Sender).sendonce(..)``."""
    rule = one_rule("forall bel(received(Sender, int(q))) do (Sender).sendonce(:q).")
    send = rule.actions[0]
    assert isinstance(send, ast.SendAction)
    assert (squash(send.receiver.text).strip("()"), send.mood, send.content.text) == (
        "Sender", ":", "q",
    )


def test_actionspecs_plain_internal_and_without_parameters() -> None:
    program = parse_agent(
        """
        init module { actionspec {
            move(X, Y) {
                pre { clear(X), clear(Y), on(X, Z), X \\= Y }
                post { not(on(X, Z)), on(X, Y) }
            }
            make(Product)@int { pre { have(Product) } post { made(Product) } }
            skip@int { pre { true } post { true } }
            pickUp{ pre{ near(_) } post{ true } }
        } }
        """
    )
    specs = {s.name: s for s in program.actionspecs}
    move, make, skip, pick = specs["move"], specs["make"], specs["skip"], specs["pickUp"]
    assert ([p.text for p in move.params], move.internal) == (["X", "Y"], False)
    assert squash(move.pre.text) == "clear(X),clear(Y),on(X,Z),X\\=Y"
    assert squash(move.post.text) == "not(on(X,Z)),on(X,Y)"
    assert ([p.text for p in make.params], make.internal) == (["Product"], True)
    assert (skip.arity, skip.internal) == (0, True)
    assert (pick.arity, pick.internal) == (0, False)


def test_environment_action_marked_at_env() -> None:
    """GOAL 5's grammar marks actions for the environment with ``@env`` (the default)."""
    program = parse_agent(
        "init module { actionspec { move(X)@env { pre { true } post { at(X) } } } }"
    )
    (spec,) = program.actionspecs
    assert (spec.name, spec.arity, spec.internal) == ("move", 1, False)
