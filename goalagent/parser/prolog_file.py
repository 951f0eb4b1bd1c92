"""Plain Prolog files (``#import "file.pl".`` and ``--load-beliefs``): each clause read by
SWI-Prolog, with its position."""

from __future__ import annotations

from pathlib import Path

from goalagent import ast
from goalagent.parser.agents import parse_clause_file


def parse_prolog_file(path: str | Path) -> tuple[ast.PrologText, ...]:
    """The clauses of a Prolog file, each read by SWI-Prolog (for ``#import``): a GOAL 6
    system's clause files are read the same way (``parse_clause_file``)."""
    return parse_clause_file(path)
