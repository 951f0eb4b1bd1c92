"""Parser tests: the file layout and the options of the language contract (modules, sections,
imports, exit/focus/order options, module parameters). ``test_parser_rules.py`` covers rules,
macros and actions; ``test_parser_text.py`` covers comments, Prolog text, positions, broken
programs reported at the exact ``file:line:col`` and the corpora under ``tests/agents/``:
``good/`` ones must parse, and every ``broken/`` one starts with ``% expect-error: LINE:COL``
(``LINE:*`` where SWI-Prolog's reader chooses the column inside the Prolog text).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from goalagent import ast
from goalagent.parser import GoalSyntaxError, parse_agent, parse_agent_file

from .shapes import literal_ops, main_rules, squash

CORPUS = Path(__file__).resolve().parents[2] / "agents"


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
