"""Where the ``goalagent`` command reports, and how it refuses a user's mistake.

Shared by the language's commands and those extensions add, so every command reports the
same way: one ``error: ...`` line on stderr and exit code 2, never a traceback.
"""

from __future__ import annotations

import re
from typing import Any

import typer
from rich.console import Console
from rich.text import Text

_UNPRINTABLE = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u200e\u200f\u202a-\u202e\u2066-\u2069]")
"""Control characters (ANSI escape sequences start with ESC, 0x1b) and the bidirectional
overrides that make a terminal show text other than what it is; newline and tab pass."""


def printable(text: str) -> str:
    """``text`` safe to print on a terminal: control characters and bidirectional overrides
    are shown as Python escapes (``\\x1b``) instead of acting on the terminal. For text that
    comes from files (names in a database, a can file, a program)."""
    return _UNPRINTABLE.sub(lambda found: found.group().encode("unicode_escape").decode(), text)


class LastingConsole(Console):
    """A Rich console for what goalagent says: text given as ``str`` is printed
    :func:`printable` (messages quote names from files: a program's path, an object's
    name), and it goes quiet when its output is gone (a closed pipe, a terminal closed:
    SIGHUP) instead of ending the process as Rich does: a run still has its saves to make,
    and they must not be lost because nobody is reading."""

    def print(self, *objects: object, **options: Any) -> None:
        super().print(*(printable(o) if isinstance(o, str) else o for o in objects), **options)

    def on_broken_pipe(self) -> None:
        self.quiet = True


err_console = LastingConsole(stderr=True, highlight=False, soft_wrap=True, emoji=False)
"""stderr: warnings, reports and errors (stdout belongs to the agents' print/1)."""
USER_ERROR = 2
"""Exit code for a user's mistake (a malformed file, an unknown name, a bad option)."""


def user_error(message: str) -> typer.Exit:
    """Print ``error: message`` on stderr (never read as markup, control characters escaped:
    messages quote names from files); raise the returned Exit to stop with USER_ERROR."""
    err_console.print(Text.assemble(("error:", "bold red"), " ", printable(message)))
    return typer.Exit(code=USER_ERROR)
