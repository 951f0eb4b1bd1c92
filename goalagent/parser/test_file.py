"""`.test2g` test files (GOAL 6+ and GOAL 5's ``masTest``): the system they run, resolved
next to the test file, its time limit, module tests and the agents' steps."""

from __future__ import annotations

from pathlib import Path

from goalagent import ast
from goalagent.parser.agents import resolve_reference
from goalagent.parser.ast_builder import build
from goalagent.parser.source import read_program_file


def parse_test(text: str, file: str = "<string>") -> ast.TestProgram:
    """Parse the text of a `.test2g` file; its system is resolved next to ``file``."""
    # a knowledge predicate may stand bare in a test condition (GOAL 5 tests)
    result, _ = build(text, file, "test_file", plain_beliefs=True)
    _, mas, mas_pos, timeout, module_tests, agent_tests = result  # type: ignore[misc]
    quoted = mas.endswith(".mas2g") or "/" in mas
    use = ast.UseClause(mas, "mas", mas_pos, quoted)
    path = resolve_reference(use, Path(file).parent)
    return ast.TestProgram(file, str(path), mas_pos, timeout, module_tests, agent_tests)


def parse_test_file(path: str | Path) -> ast.TestProgram:
    """Parse a `.test2g` file."""
    return parse_test(read_program_file(path), str(path))
