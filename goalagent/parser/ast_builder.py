"""The AST builder: the parts for `.goal` sections, conditions, GOAL 6+ module and action
files, `.mas2g` and `.test2g` files composed into one lark ``Transformer``, and ``build``
(source text -> tree -> AST objects) for every file kind.

One transformer serves every start rule of ``grammar.lark`` because the file kinds share
conditions, rules and actions (a `.test2g` holds conditions, a `.mod2g` rules) and the
Prolog-text checks; `.goal` files ``#import`` Prolog files and GOAL 5 module files.
"""

from __future__ import annotations

from contextvars import ContextVar
from functools import partial
from pathlib import Path

from lark.exceptions import VisitError

from goalagent import ast
from goalagent.kb.engine import KBError
from goalagent.parser.conditions import ConditionParts
from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.goal_sections import GoalParts
from goalagent.parser.grammar import parse_tree
from goalagent.parser.mas_sections import MasParts
from goalagent.parser.module_sections import ModuleParts
from goalagent.parser.reparse import observe
from goalagent.parser.source import Source, read_program_file
from goalagent.parser.test_sections import TestParts

# The files whose #import is being read (the innermost last).
_IMPORTING: ContextVar[tuple[Path, ...]] = ContextVar("importing", default=())


class AstBuilder(GoalParts, ConditionParts, ModuleParts, MasParts, TestParts):
    """Turns the lark tree of one file into ``goalagent.ast`` objects, checking every Prolog
    fragment with SWI-Prolog's reader. (Each part applies lark's ``v_args`` itself: lark
    wraps only the methods a class defines, not inherited ones.)"""

    def _import_prolog_file(self, path: Path) -> tuple[ast.PrologText, ...]:
        """The clauses of a Prolog file named by ``#import``."""
        clauses, _ = build(observe(partial(read_program_file, path)), str(path), "prolog_file")
        return clauses  # type: ignore[return-value]

    def _import_module_file(self, path: Path, pos: ast.Pos) -> list[ast.Module]:
        """The modules of a GOAL 5 module file named by ``#import`` (single-file syntax); a
        file that imports itself, directly or through others, is a located error (it was
        read until Python's recursion limit)."""
        chain = _IMPORTING.get() + (Path(self.source.file).resolve(),)
        if path.resolve() in chain:
            cycle = " -> ".join(p.name for p in chain[chain.index(path.resolve()):])
            raise GoalSyntaxError.at(pos, f"#import {path.name}: the files import each other "
                                     f"({cycle} -> {path.name})")
        token = _IMPORTING.set(chain)
        try:
            (_, items), _ = build(observe(partial(read_program_file, path)),  # type: ignore[misc]
                                  str(path), "agent")
        finally:
            _IMPORTING.reset(token)
        modules = [item for item in items if isinstance(item, ast.Module)]
        if not modules:
            raise GoalSyntaxError.at(pos, f"#import {path.name}: the file has no module")
        return modules


def build(text: str, file: str, start: str, *, plain_beliefs: bool = False,
          split_facts: bool = True) -> tuple[object, AstBuilder]:
    """The AST objects of ``text`` read from start rule ``start`` (agent, mas, prolog_file,
    module_file, action_file or test_file), and the builder (it keeps the macros it met).
    ``plain_beliefs``: bare literals in conditions are belief queries (newest dialect);
    ``split_facts``: a Prolog file's ``a, b.`` is two facts (not in a goals file)."""
    source = Source(text, file)
    tree = parse_tree(source, start)
    builder = AstBuilder(source)
    builder.plain_beliefs = plain_beliefs
    builder.split_facts = split_facts
    try:
        return builder.transform(tree), builder
    except VisitError as err:  # lark wraps errors raised inside callbacks
        inner = err.orig_exc
        if isinstance(inner, GoalSyntaxError):
            raise inner from None
        if isinstance(inner, KBError):  # a text SWI-Prolog refused: at the node it came from
            meta = getattr(err.obj, "meta", None)
            offset = getattr(meta, "start_pos", 0) if meta is not None else 0
            raise source.error(offset, inner.message) from None
        raise
