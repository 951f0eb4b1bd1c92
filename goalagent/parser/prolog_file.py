"""Plain Prolog files (``#import "file.pl".`` and ``--load-beliefs``): each clause read by
SWI-Prolog, with its position."""

from __future__ import annotations

from pathlib import Path

from goalagent import ast
from goalagent.parser.ast_builder import build
from goalagent.parser.source import read_program_file


def parse_prolog_file(path: str | Path) -> tuple[ast.PrologText, ...]:
    """The clauses of a Prolog file, each read by SWI-Prolog (for ``#import``)."""
    clauses, _ = build(read_program_file(path), str(path), "prolog_file")
    return clauses  # type: ignore[return-value]
