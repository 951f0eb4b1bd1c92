"""Programs parsed once per process (goalagent/parser/reparse.py): the same text parsed again
is an equal copy, never the same object; what its #imports found on disk is looked at again,
so an imported file changed, removed or put next to the program is read anew; a text that
fails fails every time."""

from __future__ import annotations

from pathlib import Path

import pytest

from goalagent.parser import GoalSyntaxError, parse_agent, parse_agent_file
from goalagent.parser.reparse import observe, parsed_once

PROGRAM = """
main module {
    knowledge { #import "facts.pl". }
    program { if bel(colour(X)) then print(X). }
}
"""


def _colours(program) -> list[str]:
    return [str(clause) for clause in program.knowledge]


def test_the_same_text_again_is_an_equal_copy(tmp_path: Path):
    (tmp_path / "facts.pl").write_text("colour(red).\n")
    file = tmp_path / "a.goal"
    file.write_text(PROGRAM)
    first, again = parse_agent_file(file), parse_agent_file(file)
    assert again == first and again is not first
    assert again.modules[0] is not first.modules[0]
    assert _colours(again) == ["colour(red)"]


def test_an_imported_file_changed_or_removed_is_read_again(tmp_path: Path):
    facts = tmp_path / "facts.pl"
    facts.write_text("colour(red).\n")
    file = tmp_path / "a.goal"
    file.write_text(PROGRAM)
    assert _colours(parse_agent_file(file)) == ["colour(red)"]
    facts.write_text("colour(blue).\ncolour(green).\n")
    assert _colours(parse_agent_file(file)) == ["colour(blue)", "colour(green)"]
    facts.unlink()
    with pytest.raises(GoalSyntaxError, match="cannot #import 'facts.pl'"):
        parse_agent_file(file)


def test_a_file_put_next_to_the_program_is_found_in_place_of_the_library(tmp_path: Path):
    """agents/garbage_disposal.goal imports the robot extension's affordance.pl; a program
    beside a file of that name reads that file instead, once it is there."""
    file = tmp_path / "a.goal"
    file.write_text(PROGRAM.replace("facts.pl", "affordance.pl"))
    from_library = parse_agent_file(file)
    assert any("afford(" in text for text in _colours(from_library))
    (tmp_path / "affordance.pl").write_text("colour(mine).\n")
    assert _colours(parse_agent_file(file)) == ["colour(mine)"]


def test_an_imported_module_file_changed_is_read_again(tmp_path: Path):
    module = tmp_path / "extra.mod2g"
    module.write_text("module extra { program { if true then print(one). } }\n")
    file = tmp_path / "a.goal"
    file.write_text('#import "extra.mod2g".\nmain module { program { if true then extra. } }\n')
    first = parse_agent_file(file)
    module.write_text("module extra { program { if true then print(two). } }\n")
    again = parse_agent_file(file)
    printed = [str(m.rules[0].actions[0]) for p in (first, again) for m in p.modules
               if m.name == "extra"]
    assert "one" in printed[0] and "two" in printed[1]


def test_warnings_come_with_every_copy():
    text = "main module { program { if bel(f(X, Y)) then print(X). } }"
    first, again = parse_agent(text), parse_agent(text)
    assert first.warnings and again.warnings == first.warnings


def test_a_text_that_fails_fails_each_time():
    text = "main module { program { if bel(f(X) then print(X). } }"
    for _ in range(2):
        with pytest.raises(GoalSyntaxError):
            parse_agent(text)


def test_a_parse_inside_another_passes_on_what_it_looked_at():
    """The outer parse depends on what the inner one observed, also when the inner one is a
    copy of an earlier parse."""
    world = {"colour": "red"}
    inner_runs: list[str] = []

    def inner() -> str:
        inner_runs.append(world["colour"])
        return observe(lambda: world["colour"])

    def outer() -> str:
        return "outer " + parsed_once("", "inner", inner)

    assert parsed_once("", "inner", inner) == "red"
    assert parsed_once("", "outer", outer) == "outer red"  # the inner one a copy here
    assert inner_runs == ["red"]
    world["colour"] = "blue"
    assert parsed_once("", "outer", outer) == "outer blue"
    assert inner_runs == ["red", "blue"]


def test_the_least_recently_used_parses_go_first_beyond_the_budget(monkeypatch):
    from goalagent.parser import reparse

    monkeypatch.setattr(reparse, "KEPT_BYTES", 3 * len(reparse.pickle.dumps("x" * 1000)))
    runs: list[str] = []

    def parse(name: str):
        return lambda: runs.append(name) or name * 1000

    for name in ("a", "b", "c", "a", "d"):  # d's keeping drops b, the least recently used
        reparse.parsed_once(name, "budget", parse(name))
    assert runs == ["a", "b", "c", "d"]
    for name in ("a", "c", "d", "b"):
        reparse.parsed_once(name, "budget", parse(name))
    assert runs == ["a", "b", "c", "d", "b"]
