"""The GOAL parser kept beside the bytecode (goalagent/parser/grammar.py): the kept one parses
as the built one does, down to each node's position; a file that does not load is built
again; nothing is kept unless asked; a changed grammar is kept under another name."""

from __future__ import annotations

from pathlib import Path

from lark import Lark, Token, Tree

from goalagent.parser.grammar import GRAMMAR, OPTIONS, cached_parser_path, load_or_build
from goalagent.parser.source import Source

ROOT = Path(__file__).resolve().parents[3]
GARBAGE = ROOT / "agents" / "garbage_disposal.goal"


def _shape(node: Tree | Token) -> tuple:
    """A node, its children and every position lark gives them."""
    if isinstance(node, Token):
        return (node.type, str(node), node.line, node.column, node.end_line, node.end_column)
    meta = node.meta
    return (node.data, meta.line, meta.column, meta.end_line, meta.end_column,
            tuple(_shape(child) for child in node.children))


def test_a_kept_parser_parses_as_the_built_one(tmp_path: Path):
    grammar, kept = GRAMMAR.read_text(), tmp_path / "__pycache__" / "grammar.lark"
    built = load_or_build(grammar, kept, keep=True)
    assert kept.is_file()
    loaded = load_or_build(grammar, kept, keep=False)
    assert loaded is not built
    text = Source(GARBAGE.read_text(), str(GARBAGE)).text  # its comments blanked
    expected = _shape(Lark(grammar, **OPTIONS).parse(text, start="agent"))
    assert _shape(built.parse(text, start="agent")) == expected
    assert _shape(loaded.parse(text, start="agent")) == expected


def test_a_kept_file_that_does_not_load_is_built_again(tmp_path: Path):
    grammar, kept = GRAMMAR.read_text(), tmp_path / "grammar.lark"
    kept.write_bytes(b"not a parser")
    parser = load_or_build(grammar, kept, keep=False)
    assert kept.read_bytes() == b"not a parser"  # not asked to keep it
    assert parser.parse("main module { program { if true then print(x). } }", start="agent")
    load_or_build(grammar, kept, keep=True)
    assert kept.read_bytes() != b"not a parser"
    load_or_build(grammar, tmp_path / "none.lark", keep=False)
    assert sorted(path.name for path in tmp_path.iterdir()) == ["grammar.lark"]


def test_another_grammar_is_kept_under_another_name():
    grammar = GRAMMAR.read_text()
    path = cached_parser_path(grammar)
    assert path.parent == GRAMMAR.with_name("__pycache__")
    assert path == cached_parser_path(grammar)
    assert path != cached_parser_path(grammar + "\n// changed\n")
