"""The AST builder: the `.goal`, condition and `.mas2g` parts composed into one lark
``Transformer``, and ``build`` (source text -> tree -> AST objects) for every file kind.

One transformer serves all three start rules of ``grammar.lark`` because `.goal` files
``#import`` Prolog files and the parts share the Prolog-text checks. GOAL 6's multi-file
format (.mod2g / .act2g / .mas2g with ``use ... as ...``) adds its start rules to the
grammar and its part here, next to the others.
"""

from __future__ import annotations

from pathlib import Path

from goalagent import ast
from goalagent.parser.conditions import ConditionParts
from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.goal_sections import GoalParts
from goalagent.parser.grammar import parse_tree
from goalagent.parser.mas_sections import MasParts
from goalagent.parser.source import Source, read_program_file


class AstBuilder(GoalParts, ConditionParts, MasParts):
    """Turns the lark tree of one file into ``goalagent.ast`` objects, checking every Prolog
    fragment with SWI-Prolog's reader. (Each part applies lark's ``v_args`` itself: lark
    wraps only the methods a class defines, not inherited ones.)"""

    def _import_prolog_file(self, path: Path) -> tuple[ast.PrologText, ...]:
        """The clauses of a Prolog file named by ``#import``."""
        clauses, _ = build(read_program_file(path), str(path), "prolog_file")
        return clauses


def build(text: str, file: str, start: str) -> tuple[object, AstBuilder]:
    """The AST objects of ``text`` read from start rule ``start`` (agent, mas or
    prolog_file), and the builder (it keeps the macros it met)."""
    source = Source(text, file)
    tree = parse_tree(source, start)
    builder = AstBuilder(source)
    try:
        return builder.transform(tree), builder
    except Exception as err:  # lark wraps errors raised inside callbacks
        inner = getattr(err, "orig_exc", None)
        if isinstance(inner, GoalSyntaxError):
            raise inner from None
        raise
