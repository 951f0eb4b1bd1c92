"""Parser tests: comments, Prolog text kept exactly, positions, broken programs reported at
the exact ``file:line:col``, the corpora and `.mas2g` files (``test_parser.py`` and
``test_parser_rules.py`` cover the constructs of the language; helpers in ``shapes.py``)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from goalagent import ast
from goalagent.parser import (
    GoalSyntaxError,
    parse_agent,
    parse_agent_file,
    parse_mas,
    parse_mas_file,
)

from .shapes import main_rules, one_rule, squash

ROOT = Path(__file__).resolve().parents[3]
EXAMPLES = ROOT / "agents" / "examples"
CORPUS = Path(__file__).resolve().parents[2] / "agents"
GOOD = sorted((CORPUS / "good").glob("*.goal"))
BROKEN = sorted((CORPUS / "broken").glob("*.goal"))
BROKEN_MAS = sorted((CORPUS / "broken").glob("*.mas2g"))
EXAMPLE_AGENTS = sorted(EXAMPLES.glob("*.goal"))
EXAMPLE_SYSTEMS = sorted(EXAMPLES.glob("*.mas2g"))


# ----------------------------------------------------------------------------- helpers


def expected_position(path: Path) -> tuple[int, int | None]:
    """The ``% expect-error: LINE:COL`` header of a broken corpus file (COL None for ``*``)."""
    header = path.read_text(encoding="utf-8").splitlines()[0]
    match = re.fullmatch(r"% expect-error: (\d+):(\d+|\*)", header)
    assert match, f"{path.name}: first line must be '% expect-error: LINE:COL'"
    col = None if match.group(2) == "*" else int(match.group(2))
    return int(match.group(1)), col


# ----------------------------------------------------------------------------- comments


def test_all_comment_kinds() -> None:
    program = parse_agent(
        """
        % a Prolog-style line comment { ' "
        /* a block comment
           over lines, with } and ' in it */
        // a C-style line comment outside Prolog text (
        init module {  // after a brace
            beliefs {
                a. % after a clause
                /* between clauses */ b.
            }
        }
        main module { /* before */ program { // after
            if bel(a) then print(done). % after a rule
        } }
        """
    )
    assert [b.text for b in program.beliefs] == ["a", "b"]
    assert len(main_rules(program)) == 1


def test_comment_characters_inside_prolog_text_are_not_comments() -> None:
    program = parse_agent(
        """
        init module {
            knowledge {
                half(X, Y) :- Y is X // 2.
                percent('100%').
                says("a /* string */ with % in it").
            }
        }
        main module { program {
            if bel(half(9, H)) then print("// not a comment").
        } }
        """
    )
    assert [k.text for k in program.knowledge] == [
        "half(X, Y) :- Y is X // 2",
        "percent('100%')",
        'says("a /* string */ with % in it")',
    ]
    action = main_rules(program)[0].actions[0]
    assert isinstance(action, ast.ActionCall) and action.args[0].text == '"// not a comment"'


def test_comment_inside_a_multi_line_condition() -> None:
    rule = one_rule(
        """
        if bel(at(Old), room(New),   % where next
               New \\= Old)           % not where we are
            then print(New).
        """
    )
    literal = rule.condition[0]
    assert isinstance(literal, ast.MentalLiteral) and literal.query is not None
    assert literal.query.variables == ("Old", "New")


# ----------------------------------------------------------------------------- Prolog text


def test_prolog_text_is_kept_exactly() -> None:
    clauses = [
        "p(X) :- X > 1, X =< 10 ; X == 0",
        "q(X) :- ( X = a -> true ; fail )",
        "r(X) :- \\+ s(X)",
        "n('it''s', 'a\\'b', \"say \\\"hi\\\"\")",
        "c({a, b}, [H|T], -3, 1.5e3, 0x1F)",
        "u(X, Y) :- X =.. Y, X @< Y",
        "close_paren(0'))",
        "open_brace(0'{)",
        "is_dot(C) :- C =:= 0'. ",
        "braces(['{', '}', '(', ')'])",
        "'quoted functor'(x)",
        ":- dynamic seen/1, done/0",
    ]
    body = "\n".join(f"    {c}." for c in clauses)
    program = parse_agent(f"init module {{ knowledge {{\n{body}\n}} }}")
    assert [k.text.rstrip() for k in program.knowledge] == [c.rstrip() for c in clauses]


def test_clause_variables_and_positions() -> None:
    text = "init module {\n  knowledge {\n    p(X, Y) :- q(Y, Z), r(Z, X).\n  }\n}\n"
    program = parse_agent(text, "vars.goal")
    clause = program.knowledge[0]
    assert clause.variables == ("X", "Y", "Z")
    assert (clause.pos.file, clause.pos.line, clause.pos.col) == ("vars.goal", 3, 5)
    assert text[clause.pos.offset:].startswith("p(X, Y)")


def test_positions_of_modules_literals_and_actionspecs() -> None:
    text = (
        "init module {\n"
        "  actionspec {\n"
        "    go(X) { pre { true } post { true } }\n"
        "  }\n"
        "}\n"
        "main module {\n"
        "  program {\n"
        "    if true, bel(p(X)) then go(X).\n"
        "  }\n"
        "}\n"
    )
    program = parse_agent(text, "pos.goal")
    main = program.module("main")
    assert main is not None and (main.pos.line, main.pos.col) == (6, 1)
    spec = program.actionspecs[0]
    assert (spec.pos.line, spec.pos.col) == (3, 5)
    rule = main.rules[0]
    assert [(lit.pos.line, lit.pos.col) for lit in rule.condition] == [(8, 8), (8, 14)]
    assert (rule.actions[0].pos.line, rule.actions[0].pos.col) == (8, 29)


# ----------------------------------------------------------------------------- errors


def test_error_string_is_file_line_col_message() -> None:
    with pytest.raises(GoalSyntaxError) as caught:
        parse_agent("main module {\n  program {\n    if bel(a) print(b).\n  }\n}\n", "x.goal")
    err = caught.value
    assert (err.file, err.line, err.col) == ("x.goal", 3, 15)
    assert err.message
    assert str(err) == f"x.goal:3:15: {err.message}"


@pytest.mark.parametrize("path", BROKEN, ids=lambda p: p.name)
def test_broken_program_is_reported_at_the_exact_place(path: Path) -> None:
    line, col = expected_position(path)
    with pytest.raises(GoalSyntaxError) as caught:
        parse_agent_file(path)
    err = caught.value
    assert err.file == str(path)
    assert err.line == line, str(err)
    if col is not None:
        assert err.col == col, str(err)
    else:  # SWI-Prolog's reader chooses the column; it must lie on that line's text
        text_line = path.read_text(encoding="utf-8").splitlines()[line - 1]
        assert 1 <= err.col <= len(text_line) + 1, str(err)
    assert str(err).startswith(f"{path}:{err.line}:{err.col}: ")
    assert "Traceback" not in err.message


@pytest.mark.parametrize("path", BROKEN_MAS, ids=lambda p: p.name)
def test_broken_mas_is_reported_at_the_exact_place(path: Path) -> None:
    line, col = expected_position(path)
    with pytest.raises(GoalSyntaxError) as caught:
        parse_mas_file(path)
    assert (caught.value.line, caught.value.col) == (line, col), str(caught.value)


def test_missing_file_is_a_clean_error(tmp_path: Path) -> None:
    with pytest.raises(GoalSyntaxError) as caught:
        parse_agent_file(tmp_path / "nowhere.goal")
    assert caught.value.file == str(tmp_path / "nowhere.goal")


def test_prolog_error_message_names_the_problem() -> None:
    with pytest.raises(GoalSyntaxError) as caught:
        parse_agent("main module { program { if bel(X == == Y) then print(X). } }")
    assert caught.value.line == 1
    assert 32 <= caught.value.col <= 42  # inside the text of bel(..)


# ----------------------------------------------------------------------------- corpora


@pytest.mark.parametrize("path", GOOD, ids=lambda p: p.name)
def test_good_corpus_parses(path: Path) -> None:
    program = parse_agent_file(path)
    assert program.modules


def test_every_construct_program() -> None:
    program = parse_agent_file(CORPUS / "good" / "every_construct.goal")
    assert program.name == "everything"
    assert {m.name for m in program.modules} == {"init", "main", "event", "sub", "other", "third"}
    assert [m.name for m in program.macros] == ["ready", "has", "pair"]
    sends = [a for r in main_rules(program) for a in r.actions if isinstance(a, ast.SendAction)]
    assert [(s.receiver.text, s.name, s.mood) for s in sends] == [
        ("bob", "send", ":"), ("allother", "sendonce", "!"), ("all", "send", "?"),
        ("me", "send", ":"),
    ]


@pytest.mark.parametrize("path", EXAMPLE_AGENTS, ids=lambda p: p.name)
def test_example_agents_parse_without_warnings(path: Path) -> None:
    program = parse_agent_file(path)
    assert program.warnings == ()
    first = path.read_text(encoding="utf-8").splitlines()[0]
    assert first.startswith(f"% {path.name}:"), "each example starts by saying what it shows"


# ----------------------------------------------------------------------------- .mas2g


def test_mas_without_environment() -> None:
    mas = parse_mas_file(EXAMPLES / "coffee.mas2g")
    assert mas.environment is None and mas.env_init == ()
    assert [(a.path, a.name) for a in mas.agentfiles] == [
        ("coffee_maker.goal", "maker"), ("coffee_grinder.goal", "grinder"),
    ]
    assert [(r.agent_name, r.agentfile, r.on_entity) for r in mas.launches] == [
        ("maker", "maker", False), ("grinder", "grinder", False),
    ]


def test_mas_with_environment_and_entity_launch_rules() -> None:
    mas = parse_mas_file(EXAMPLES / "blocks_team.mas2g")
    assert mas.environment == "blocksworld"
    init = dict(mas.env_init)
    assert squash(init["state"].text) == "[on(c,a),on(a,table),on(d,b),on(b,table)]"
    assert [(r.agent_name, r.on_entity, r.entity_type, r.max) for r in mas.launches] == [
        ("builder", True, "gripper", 1), ("helper", True, "gripper", 1),
    ]


def test_mas_forms_seen_in_real_files() -> None:
    mas = parse_mas(
        """
        environment{
            env = "tower" .
            % a comment
            init = [map = "random", speed = 0.5, robots = 3] .
        }
        agentfiles{
            %"old.goal" [name = old] .
            "bot.goal" [name = bot, number = 3] .
            "helper.goal" .
        }
        launchpolicy{
            when [type=human, max=1]@env do launch * : bot .
            when entity@env do launch bot : bot .
            launch helper : helper.
        }
        """,
        "real.mas2g",
    )
    assert mas.environment == "tower"
    assert [k for k, _ in mas.env_init] == ["map", "speed", "robots"]
    assert [(a.path, a.name, a.number) for a in mas.agentfiles] == [
        ("bot.goal", "bot", 3), ("helper.goal", "helper", 1),
    ]
    star, entity, plain = mas.launches
    assert (star.agent_name, star.entity_type, star.max, star.on_entity) == ("*", "human", 1, True)
    assert (entity.agent_name, entity.on_entity, entity.max) == ("bot", True, None)
    assert (plain.agent_name, plain.on_entity) == ("helper", False)
