"""Program text as the grammar sees it: comments blanked out, offsets mapped to line:col.

Comments are blanked by hand rather than in the grammar because ``//`` starts a comment only
outside Prolog text, which a context-free lexer cannot tell; blanking keeps every offset
valid, so positions in errors and in the AST point into the original file. The same pass
bounds bracket nesting (``MAX_NESTING``), so no later stage meets a text nested deeper than
it can take; files are read only when they are regular files of a bounded size
(``ondisk.read_bounded``), so ``/dev/zero``, a FIFO or a directory is refused at once.
"""

from __future__ import annotations

import bisect
import re
from pathlib import Path

from goalagent import ast
from goalagent.parser.errors import GoalSyntaxError
from ondisk import read_bounded

MAX_NESTING = 200
"""Deepest nesting of ``( [ {`` accepted in a program (SWI's reader and Python's term
conversion recurse per level; real programs stay far below)."""
MAX_PROGRAM_BYTES = 512 * 2**10
"""Largest `.goal`, `.mas2g`, `.mod2g` or `#import`ed `.pl` file read: parsing costs about
1 kB of memory and 20 µs per byte of program (a 2 MB file of facts took 41 s and 2.5 GB),
the largest program shipped is 28 kB, and facts in bulk are read by ``--load-beliefs``."""
MAX_FACT_FILE_BYTES = 64 * 2**20
"""Largest ``--load-beliefs`` file read (a million afford/6 facts take about 55 MB)."""
_OPENING, _CLOSING = "([{", ")]}"


class Source:
    """A program text with comments blanked out and offset -> line/column mapping."""

    def __init__(self, text: str, file: str) -> None:
        self.file = file
        self.original = text
        self._line_starts = [0] + [m.end() for m in re.finditer(r"\n", text)]
        self.text = self._blank_comments(text)

    def pos(self, offset: int) -> ast.Pos:
        """The position of a character offset."""
        line = bisect.bisect_right(self._line_starts, offset)
        col = offset - self._line_starts[line - 1] + 1
        return ast.Pos(self.file, line, col, offset)

    def error(self, offset: int, message: str) -> GoalSyntaxError:
        """A syntax error at a character offset."""
        return GoalSyntaxError.at(self.pos(offset), message)

    def fragment(self, start: int, end: int) -> tuple[str, int]:
        """The stripped text between two offsets and the offset where it starts."""
        raw = self.text[start:end]
        stripped = raw.lstrip()
        return stripped.rstrip(), start + len(raw) - len(stripped)

    def _blank_comments(self, text: str) -> str:
        """Replace comments by spaces (newlines kept) so that offsets stay valid.

        ``%`` and ``/* */`` comments are Prolog's own; ``//`` starts a comment only outside
        Prolog text, i.e. where it begins a line or follows ``{ } ] .``.
        """
        out = list(text)
        i, n = 0, len(text)
        depth = 0
        while i < n:
            ch = text[i]
            if ch in _OPENING:
                depth += 1
                if depth > MAX_NESTING:
                    raise self.error(i, f"brackets nested more than {MAX_NESTING} deep")
                i += 1
            elif ch in _CLOSING:
                depth = max(depth - 1, 0)
                i += 1
            elif ch in "'\"`":
                if ch == "'" and i > 0 and text[i - 1] == "0" and (
                    i < 2 or not (text[i - 2].isalnum() or text[i - 2] == "_")
                ):
                    i += 3 if text[i + 1 : i + 2] == "\\" else 2  # 0'c character code
                    continue
                i = self._skip_quoted(text, i)
            elif ch == "%":
                i = self._blank_until(out, text, i, "\n")
            elif text.startswith("/*", i):
                end = text.find("*/", i + 2)
                if end < 0:
                    raise self.error(i, "unterminated /* comment")
                for k in range(i, end + 2):
                    if out[k] != "\n":
                        out[k] = " "
                i = end + 2
            elif text.startswith("//", i) and self._slash_comment_allowed(text, i):
                i = self._blank_until(out, text, i, "\n")
            else:
                i += 1
        return "".join(out)

    def _skip_quoted(self, text: str, start: int) -> int:
        """The offset after the quoted text that starts at ``start``."""
        quote = text[start]
        i = start + 1
        while i < len(text):
            ch = text[i]
            if ch == "\\":
                i += 2
            elif ch == quote:
                if text[i + 1 : i + 2] == quote:
                    i += 2
                else:
                    return i + 1
            else:
                i += 1
        raise self.error(start, f"unterminated quoted text starting with {quote}")

    @staticmethod
    def _blank_until(out: list[str], text: str, start: int, stop: str) -> int:
        """Blanks ``out`` from ``start`` up to the next ``stop`` (or the end); its offset."""
        end = text.find(stop, start)
        end = len(text) if end < 0 else end
        for k in range(start, end):
            out[k] = " "
        return end

    @staticmethod
    def _slash_comment_allowed(text: str, i: int) -> bool:
        """True when ``//`` at ``i`` starts a comment: first on its line or after { } ] ."""
        k = i - 1
        while k >= 0 and text[k] in " \t\r":
            k -= 1
        return k < 0 or text[k] in "\n{}]."


def read_program_file(path: str | Path, limit: int = MAX_PROGRAM_BYTES) -> str:
    """The text of a program file (a regular file of at most ``limit`` bytes), UTF-8 or else
    Latin-1 (GOAL's Windows users wrote comments in cp1252/Latin-1); a missing or unreadable
    file is a located error."""
    try:
        data = read_bounded(path, limit)
    except FileNotFoundError:
        raise GoalSyntaxError(str(path), 1, 1, "no such file") from None
    except (OSError, ValueError) as err:  # ValueError: a NUL byte in the path
        reason = getattr(err, "strerror", None) or err
        raise GoalSyntaxError(str(path), 1, 1, f"cannot read file: {reason}") from None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:  # GOAL read files in the platform's 8-bit encoding
        return data.decode("latin-1")
