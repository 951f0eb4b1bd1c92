"""Parser tests: every construct of the language contract (file layout, options, rules,
macros, actions). ``test_parser_text.py`` covers comments, Prolog text, positions, broken
programs reported at the exact ``file:line:col`` and the corpora under ``tests/agents/``:
``good/`` ones must parse, and every ``broken/`` one starts with ``% expect-error: LINE:COL``
(``LINE:*`` where SWI-Prolog's reader chooses the column inside the Prolog text).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from goalagent import ast
from goalagent.parser import (
    GoalSyntaxError,
    parse_agent,
    parse_agent_file,
)

ROOT = Path(__file__).resolve().parents[3]
EXAMPLES = ROOT / "agents" / "examples"
CORPUS = Path(__file__).resolve().parents[2] / "agents"
GOOD = sorted((CORPUS / "good").glob("*.goal"))
BROKEN = sorted((CORPUS / "broken").glob("*.goal"))
BROKEN_MAS = sorted((CORPUS / "broken").glob("*.mas2g"))
EXAMPLE_AGENTS = sorted(EXAMPLES.glob("*.goal"))
EXAMPLE_SYSTEMS = sorted(EXAMPLES.glob("*.mas2g"))


# ----------------------------------------------------------------------------- helpers


def squash(text: str) -> str:
    """Prolog text without white space, to compare fragments independent of layout."""
    return re.sub(r"\s+", "", text)


def main_rules(program: ast.AgentProgram) -> tuple[ast.Rule, ...]:
    """The rules of the main module (which must exist)."""
    main = program.module("main")
    assert main is not None, "no main module"
    return main.rules


def one_rule(body: str) -> ast.Rule:
    """The single rule of a main module whose program section is ``body``."""
    rules = main_rules(parse_agent(f"main module {{ program {{ {body} }} }}"))
    assert len(rules) == 1
    return rules[0]


def literal_ops(condition: ast.Condition) -> list[str]:
    """The operators of a condition, ``not`` for a NotLiteral."""
    return ["not" if isinstance(lit, ast.NotLiteral) else lit.op for lit in condition]


def expected_position(path: Path) -> tuple[int, int | None]:
    """The ``% expect-error: LINE:COL`` header of a broken corpus file (COL None for ``*``)."""
    header = path.read_text(encoding="utf-8").splitlines()[0]
    match = re.fullmatch(r"% expect-error: (\d+):(\d+|\*)", header)
    assert match, f"{path.name}: first line must be '% expect-error: LINE:COL'"
    col = None if match.group(2) == "*" else int(match.group(2))
    return int(match.group(1)), col


# ----------------------------------------------------------------------------- file layout


def test_minimal_program_without_wrapper() -> None:
    program = parse_agent("main module { program { if true then print(hello). } }")
    assert [m.kind for m in program.modules] == ["main"]
    rule = main_rules(program)[0]
    assert rule.kind == "if"
    assert literal_ops(rule.condition) == ["true"]
    assert [(a.name, [t.text for t in a.args]) for a in rule.actions] == [("print", ["hello"])]


def test_wrapper_is_optional_and_names_the_agent() -> None:
    body = """
        init module { beliefs { count(0). } }
        main module [exit=nogoals] { program { if bel(count(N)) then print(N). } }
    """
    wrapped = parse_agent(f"main: counter {{ {body} }}")
    bare = parse_agent(body)
    assert wrapped.name == "counter"
    assert [(m.name, m.kind, m.exit) for m in wrapped.modules] == [
        (m.name, m.kind, m.exit) for m in bare.modules
    ]
    assert [b.text for b in wrapped.beliefs] == [b.text for b in bare.beliefs] == ["count(0)"]


def test_unwrapped_file_is_named_after_its_file(tmp_path: Path) -> None:
    path = tmp_path / "robot_one.goal"
    path.write_text("main module { program { if true then print(x). } }", encoding="utf-8")
    program = parse_agent_file(path)
    assert program.name == "robot_one"
    assert program.file == str(path)


def test_init_module_sections_are_gathered() -> None:
    program = parse_agent(
        """
        init module {
            knowledge {
                block(a). block(b).
                clear(X) :- block(X), \\+ on(_, X).
            }
            beliefs {
                on(a, b).
                on(b, table).
            }
            goals {
                on(b, a), on(a, table).
                tidy.
            }
            actionspec {
                move(X, Y) { pre { clear(X), clear(Y) } post { on(X, Y) } }
            }
        }
        """
    )
    assert [k.text for k in program.knowledge] == [
        "block(a)",
        "block(b)",
        "clear(X) :- block(X), \\+ on(_, X)",
    ]
    assert [b.text for b in program.beliefs] == ["on(a, b)", "on(b, table)"]
    # One goal per dot: a comma-separated conjunction is ONE goal.
    assert [squash(g.text) for g in program.goals] == ["on(b,a),on(a,table)", "tidy"]
    assert [(s.name, s.arity) for s in program.actionspecs] == [("move", 2)]
    init = program.module("init")
    assert init is not None and init.kind == "init"
    assert len(init.knowledge) == 3 and len(init.goals) == 2


def test_sections_in_any_order_and_in_other_modules_are_global() -> None:
    program = parse_agent(
        """
        init module {
            actionspec { go { pre { true } post { gone } } }
            beliefs { here. }
        }
        main module {
            knowledge { near(X) :- here, X = home. }
            program { if bel(near(X)) then go. }
        }
        module helper {
            beliefs { helping. }
            program { if true then go. }
        }
        """
    )
    assert [b.text for b in program.beliefs] == ["here", "helping"]
    assert [k.text for k in program.knowledge] == ["near(X) :- here, X = home"]
    main = program.module("main")
    helper = program.module("helper")
    assert main is not None and [k.text for k in main.knowledge] == ["near(X) :- here, X = home"]
    assert helper is not None and [b.text for b in helper.beliefs] == ["helping"]
    assert [s.name for s in program.actionspecs] == ["go"]


def test_top_level_sections_without_modules() -> None:
    program = parse_agent_file(CORPUS / "good" / "goal3_top_level.goal")
    assert program.name == "oldStyle"
    assert [squash(g.text) for g in program.goals] == ["on(a,b)"]
    assert len(main_rules(program)) == 1
    assert [s.name for s in program.actionspecs] == ["move"]


def test_empty_sections_are_allowed() -> None:
    program = parse_agent(
        """
        init module {
            knowledge { % only a comment
            }
            beliefs { }
            goals {}
            actionspec { }
        }
        main module { program { } }
        event module { program { } }
        """
    )
    assert program.knowledge == program.beliefs == program.goals == ()
    assert program.actionspecs == ()
    assert main_rules(program) == ()


def test_import_of_a_prolog_file_adds_knowledge(tmp_path: Path) -> None:
    (tmp_path / "coffee.pl").write_text(
        "% shared knowledge\nrequires(coffee, water).\nrequires(coffee, grounds).\n",
        encoding="utf-8",
    )
    agent = tmp_path / "maker.goal"
    agent.write_text(
        'init module {\n    #import "coffee.pl".\n    beliefs { have(water). }\n}\n',
        encoding="utf-8",
    )
    program = parse_agent_file(agent)
    assert [k.text for k in program.knowledge] == [
        "requires(coffee, water)", "requires(coffee, grounds)",
    ]
    assert program.knowledge[1].pos.file == str(tmp_path / "coffee.pl")
    assert program.knowledge[1].pos.line == 3


def test_import_errors_are_located(tmp_path: Path) -> None:
    agent = tmp_path / "maker.goal"
    agent.write_text('init module {\n    #import "missing.pl".\n}\n', encoding="utf-8")
    with pytest.raises(GoalSyntaxError) as missing:
        parse_agent_file(agent)
    assert (missing.value.file, missing.value.line) == (str(agent), 2), str(missing.value)
    (tmp_path / "bad.pl").write_text("ok(1).\nbroken(a b).\n", encoding="utf-8")
    agent.write_text('init module {\n    #import "bad.pl".\n}\n', encoding="utf-8")
    with pytest.raises(GoalSyntaxError) as bad:
        parse_agent_file(agent)
    assert (bad.value.file, bad.value.line) == (str(tmp_path / "bad.pl"), 2), str(bad.value)


# ----------------------------------------------------------------------------- options


@pytest.mark.parametrize("value", ["always", "never", "nogoals", "noaction"])
def test_exit_option(value: str) -> None:
    program = parse_agent(f"main module [exit={value}] {{ program {{ }} }}")
    main = program.module("main")
    assert main is not None and main.exit == value


@pytest.mark.parametrize("value", ["none", "new", "select", "filter"])
def test_focus_option(value: str) -> None:
    program = parse_agent(
        f"module m [focus={value}] {{ program {{ if true then print(x). }} }}"
        " main module { program { if true then m. } }"
    )
    module = program.module("m")
    assert module is not None and module.focus == value and module.kind == "user"


@pytest.mark.parametrize("value", ["linear", "linearall", "random", "randomall"])
def test_order_option(value: str) -> None:
    program = parse_agent(f"main module {{ program [order={value}] {{ }} }}")
    main = program.module("main")
    assert main is not None and main.order == value


def test_options_combined_and_glued_to_keywords() -> None:
    program = parse_agent(
        """
        main module[exit=nogoals]{ program[order=random]{ if true then m. } }
        module m [focus=select, exit=always] {
            program [order=linearall] { if true then print(a). }
        }
        """
    )
    main, module = program.module("main"), program.module("m")
    assert main is not None and (main.exit, main.order) == ("nogoals", "random")
    assert module is not None
    assert (module.focus, module.exit, module.order) == ("select", "always", "linearall")


def test_options_default_to_none() -> None:
    program = parse_agent("init module { } main module { program { } } event module { }")
    for module in program.modules:
        assert (module.exit, module.focus, module.order) == (None, None, None)


def test_user_module_with_parameters_and_its_call() -> None:
    program = parse_agent(
        """
        main module { program { if bel(task(T)) then chore(T, me). } }
        module chore(Task, Who) [exit=noaction] {
            program { if true then print(Task) + print(Who). }
        }
        """
    )
    chore = program.module("chore")
    assert chore is not None
    assert (chore.kind, chore.arity, [p.text for p in chore.params]) == ("user", 2, ["Task", "Who"])
    call = main_rules(program)[0].actions[0]
    assert isinstance(call, ast.ActionCall)
    assert (call.name, [a.text for a in call.args]) == ("chore", ["T", "me"])


def test_module_parameters_are_bound_not_singletons() -> None:
    program = parse_agent(
        """
        main module { program { if bel(task(T)) then chore(T). } }
        module chore(Task) { program { if true then print(Task). } }
        """
    )
    assert program.warnings == ()


def test_singleton_variables_are_warnings_with_their_place() -> None:
    program = parse_agent("main module {\n program {\n  if bel(p(X)) then print(y).\n } }",
                          "single.goal")
    assert len(program.warnings) == 1
    assert program.warnings[0].startswith("single.goal:3:3: ")
    assert "X" in program.warnings[0]


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
