"""The parser's tables kept between processes (goalagent.parser.parser_tables): the saved
parser parses as the built one does, and a missing, stale, corrupt or foreign file is rebuilt
and replaced, never trusted."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from goalagent.parser import grammar, parser_tables
from tests.conftest import goalagent

GRAMMAR = Path(grammar.__file__).with_name("grammar.lark").read_text(encoding="utf-8")
OPTIONS = {"parser": "lalr", "lexer": "contextual", "start": ["agent", "prolog_file"],
           "propagate_positions": True, "maybe_placeholders": False}
AGENT = """main module {
    program {
        if bel(p(X)), X > 1 then insert(q(X)).
    }
}
"""


@pytest.fixture
def cache(monkeypatch, tmp_path) -> Path:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    return tmp_path / "goalagent" / parser_tables.TABLES_FILE


def _positions(tree) -> list[tuple]:
    return [(sub.data, sub.meta.line, sub.meta.column, sub.meta.end_pos)
            for sub in tree.iter_subtrees()]


def test_the_saved_parser_parses_as_the_built_one(cache):
    built = parser_tables.parser(GRAMMAR, **OPTIONS)
    assert cache.read_bytes().startswith(parser_tables.tables_key(GRAMMAR, OPTIONS) + b"\n")
    saved_at = cache.stat().st_mtime_ns
    loaded = parser_tables.parser(GRAMMAR, **OPTIONS)
    assert cache.stat().st_mtime_ns == saved_at  # read, not written again
    assert loaded is not built
    one, two = built.parse(AGENT, start="agent"), loaded.parse(AGENT, start="agent")
    assert one == two
    assert _positions(one) == _positions(two)


def _rebuilt(cache: Path, spoil) -> None:
    parser_tables.parser(GRAMMAR, **OPTIONS)
    spoil(cache)
    inode = cache.stat().st_ino
    tree = parser_tables.parser(GRAMMAR, **OPTIONS).parse(AGENT, start="agent")
    assert tree.data == "agent"
    assert cache.stat().st_ino != inode  # replaced (atomically: a new file)
    assert cache.read_bytes().startswith(parser_tables.tables_key(GRAMMAR, OPTIONS) + b"\n")
    assert cache.stat().st_mode & 0o022 == 0


@pytest.mark.parametrize("spoil", [
    pytest.param(lambda p: p.write_bytes(p.read_bytes()[:5000]), id="cut short"),
    pytest.param(lambda p: p.write_bytes(b"goalagent parser tables 00\n" + p.read_bytes()),
                 id="stale key"),
    pytest.param(lambda p: p.write_bytes(p.read_bytes().split(b"\n", 1)[0] + b"\nnot a pickle"),
                 id="corrupt tables"),
    pytest.param(lambda p: p.chmod(0o666), id="writable by others"),
])
def test_a_spoiled_file_is_rebuilt_and_replaced(cache, spoil):
    _rebuilt(cache, spoil)


def test_other_options_or_another_grammar_do_not_use_the_saved_tables(cache):
    parser_tables.parser(GRAMMAR, **OPTIONS)
    other = {**OPTIONS, "start": ["prolog_file"]}
    assert parser_tables.tables_key(GRAMMAR, other) != parser_tables.tables_key(GRAMMAR, OPTIONS)
    assert parser_tables.tables_key(GRAMMAR + "\n", OPTIONS) != parser_tables.tables_key(
        GRAMMAR, OPTIONS)
    with pytest.raises(Exception, match="agent"):  # the start symbol is not in this parser
        parser_tables.parser(GRAMMAR, **other).parse(AGENT, start="agent")


def test_a_cache_that_cannot_be_written_only_costs_time(monkeypatch, tmp_path):
    blocked = tmp_path / "file-not-folder"
    blocked.write_text("")
    monkeypatch.setenv("XDG_CACHE_HOME", str(blocked))
    tree = parser_tables.parser(GRAMMAR, **OPTIONS).parse(AGENT, start="agent")
    assert tree.data == "agent"


def test_the_command_line_saves_the_tables_and_checks_alike_with_them(tmp_path):
    agent = tmp_path / "a.goal"
    agent.write_text(AGENT + "oops")
    env = {"XDG_CACHE_HOME": str(tmp_path / "cache")}
    first, second = (goalagent("check", str(agent), env=env) for _ in range(2))
    assert first.returncode == second.returncode == 2
    assert first.stderr == second.stderr
    assert f"{agent}:6:1" in first.stderr
    saved = tmp_path / "cache" / "goalagent" / parser_tables.TABLES_FILE
    assert saved.stat().st_mode & 0o022 == 0
    assert os.access(saved, os.R_OK)
