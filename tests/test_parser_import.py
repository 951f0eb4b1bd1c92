"""``#import "file.pl".`` loads a Prolog file's clauses as knowledge; other imports are refused."""

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


def test_importing_a_module_file_is_refused_clearly(tmp_path: Path) -> None:
    (tmp_path / "a.goal").write_text('#import "event.mod2g".\n')
    with pytest.raises(GoalSyntaxError, match="only Prolog .* files can be imported"):
        parse_agent_file(tmp_path / "a.goal")
