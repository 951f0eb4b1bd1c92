"""Every syntax error of a file, not only the first (``goalagent check``): after an error the
statement holding it -- the clause, rule, option or entry from the end of the previous one
to its own end ``.`` at the same brace depth -- is blanked out (newlines kept, so every
later position stays where it is) and the file is read again.

A per-statement resync is written here rather than taken from lark's error recovery
(``on_error``) because an error is found not only by the grammar but also by SWI-Prolog's
reader and the AST builder after the parse; blanking the statement serves all three.
"""

from __future__ import annotations

from collections.abc import Callable

from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.source import Source

MAX_SEARCHED = 200
"""Errors looked for in one file at most (each costs a parse)."""
_BOUNDS = ("more than", "nested more", "larger than", "unterminated")
"""Words of the errors about a bound passed (an input built to be too big or a text left
open): the search ends there, as what follows would be the first error's echoes."""


def later_errors(text: str, file: str, first: GoalSyntaxError,
                 parse: Callable[[str, str], object]) -> list[GoalSyntaxError]:
    """The errors of ``text`` after ``first`` (the error ``parse`` raised for it), each
    found after blanking the statements of those before; errors in other files (imported
    ones) end the search. When the text left parses, ``parse`` may return the errors it
    finds in the result (a list), which are added."""
    errors: list[GoalSyntaxError] = []
    if any(words in first.message for words in _BOUNDS):
        return errors
    error = first
    seen = {(first.line, first.col)}
    while len(errors) < MAX_SEARCHED and error.file == file:
        blanked = _blank_statement(text, _offset(text, error.line, error.col))
        if blanked == text:
            break
        text = blanked
        try:
            found = parse(text, file)
            if isinstance(found, list):
                errors.extend(found)
            break
        except GoalSyntaxError as err:
            if (err.line, err.col) in seen and err.file == file:
                break
            seen.add((err.line, err.col))
            errors.append(err)
            error = err
    return errors


def _offset(text: str, line: int, col: int) -> int:
    """The character offset of a 1-based line and column."""
    start = 0
    for _ in range(line - 1):
        start = text.find("\n", start) + 1
        if start == 0:
            return len(text)
    return min(start + col - 1, len(text))


def _blank_statement(text: str, offset: int) -> str:
    """``text`` with the statement around ``offset`` replaced by blanks (an option list
    ``[..]`` after a keyword or file name is a statement of its own)."""
    try:
        plain = Source(text, "").text  # comments blanked: their dots and braces do not count
    except GoalSyntaxError:
        plain = text
    options = _option_list(plain, offset)
    start, end = options if options else (_statement_start(plain, offset),
                                          _statement_end(plain, offset))
    if not options and plain[offset:offset + 1] == "}" and plain[start:offset].strip():
        end = offset  # a statement cut short by the brace after it: the brace stays
    if end <= start:
        return text
    return text[:start] + "".join(c if c == "\n" else " " for c in text[start:end]) + text[end:]


def _is_end_dot(text: str, index: int) -> bool:
    return text[index] == "." and (index + 1 == len(text) or text[index + 1] in " \t\r\n%}")


def _option_list(text: str, offset: int) -> tuple[int, int] | None:
    """The span of the ``[..]`` holding ``offset`` when it follows a word or a string (module,
    program and agent file options), else None."""
    depth = 0
    for index in range(min(offset, len(text)) - 1, -1, -1):
        char = text[index]
        if char in ")]}":
            depth += 1
        elif char in "([{":
            if depth:
                depth -= 1
                continue
            before = text[:index].rstrip()
            if char != "[" or not before or not (before[-1].isalnum() or before[-1] == '"'):
                return None
            close = text.find("]", offset)
            return (index, close + 1) if close >= 0 else None
    return None


def _statement_start(text: str, offset: int) -> int:
    """After the end ``.``, ``{`` or ``}`` before ``offset`` at its brace depth."""
    depth = 0
    for index in range(min(offset, len(text)) - 1, -1, -1):
        char = text[index]
        if char == "}":
            if depth == 0:
                return index + 1
            depth += 1
        elif char == "{":
            if depth == 0:
                return index + 1
            depth -= 1
        elif depth == 0 and _is_end_dot(text, index):
            return index + 1
    return 0


def _statement_end(text: str, offset: int) -> int:
    """After the end ``.`` from ``offset`` on at its brace depth, or before the ``}`` that
    closes it; a stray ``}`` at ``offset`` is the statement itself."""
    if offset < len(text) and text[offset] in ")]}":
        return offset + 1
    depth = 0
    for index in range(offset, len(text)):
        char = text[index]
        if char == "{":
            depth += 1
        elif char == "}":
            if depth == 0:
                return index
            depth -= 1
        elif depth == 0 and _is_end_dot(text, index):
            return index + 1
    return len(text)
