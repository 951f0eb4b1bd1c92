"""Where the ``goalagent`` command reports, and how it refuses a user's mistake.

Shared by the language's commands and those extensions add, so every command reports the
same way: one ``error: ...`` line on stderr and exit code 2, never a traceback.
"""

from __future__ import annotations

import typer
from rich.console import Console
from rich.text import Text

err_console = Console(stderr=True, highlight=False, soft_wrap=True, emoji=False)
"""stderr: warnings, reports and errors (stdout belongs to the agents' print/1)."""
USER_ERROR = 2
"""Exit code for a user's mistake (a malformed file, an unknown name, a bad option)."""


def user_error(message: str) -> typer.Exit:
    """Print ``error: message`` on stderr; raise the returned Exit to stop with USER_ERROR."""
    err_console.print(Text.assemble(("error:", "bold red"), " ", message))
    return typer.Exit(code=USER_ERROR)
