"""``#import "file.pl".`` loads a Prolog file's clauses as knowledge (also inside
``knowledge{}``, and without the extension as GOAL 5 writes it); ``#import "m.mod2g".``
adds the modules of a GOAL 5 module file."""

from __future__ import annotations

import io
from pathlib import Path

import pytest

from goalagent.agent import Agent
from goalagent.parser import GoalSyntaxError, parse_agent_file


def test_imported_prolog_clauses_become_knowledge(tmp_path: Path) -> None:
    (tmp_path / "coffee.pl").write_text("requires(coffee, water).\n"
                                        "needs(X, Y) :- requires(X, Y).\n")
    (tmp_path / "a.goal").write_text('init module { #import "coffee.pl". }\n'
                                     "main module { program { if bel(needs(coffee, P)) "
                                     "then print(P). } }\n")
    agent = Agent.from_file(tmp_path / "a.goal", output=io.StringIO())
    agent.step()
    assert agent.output.getvalue() == "water\n"


def test_syntax_error_in_an_imported_file_points_into_that_file(tmp_path: Path) -> None:
    (tmp_path / "bad.pl").write_text("ok(1).\nbroken(.\n")
    (tmp_path / "a.goal").write_text('init module { #import "bad.pl". }\n')
    with pytest.raises(GoalSyntaxError) as err:
        parse_agent_file(tmp_path / "a.goal")
    assert err.value.file.endswith("bad.pl") and err.value.line == 2


def test_a_goal5_module_file_adds_its_modules(tmp_path: Path) -> None:
    (tmp_path / "greet.mod2g").write_text(
        "module greet [exit=always] { program { if true then print(hello). } }\n")
    (tmp_path / "a.goal").write_text('#import "greet.mod2g".\n'
                                     "main module [exit=always] { program { "
                                     "if true then greet. } }\n")
    agent = Agent.from_file(tmp_path / "a.goal", output=io.StringIO())
    agent.run(max_cycles=3)
    assert agent.output.getvalue() == "hello\n"
    assert [m.name for m in agent.program.modules] == ["greet", "main"]


def test_import_inside_knowledge_without_extension(tmp_path: Path) -> None:
    (tmp_path / "facts.pl").write_text("colour(red).\n")
    (tmp_path / "a.goal").write_text('init module { knowledge { #import "facts". '
                                     "likes(X) :- colour(X). } }\n"
                                     "main module [exit=always] { program { "
                                     "if bel(likes(C)) then print(C). } }\n")
    agent = Agent.from_file(tmp_path / "a.goal", output=io.StringIO())
    agent.run(max_cycles=2)
    assert agent.output.getvalue() == "red\n"


def test_importing_a_missing_file_is_located(tmp_path: Path) -> None:
    (tmp_path / "a.goal").write_text('\n  #import "event.mod2g".\n')
    with pytest.raises(GoalSyntaxError, match="cannot #import 'event.mod2g': no such file"
                       ) as err:
        parse_agent_file(tmp_path / "a.goal")
    assert (err.value.line, err.value.col) == (2, 11)
