"""The errors of goalagent.kb: user-facing, each with a readable message (and a source
position when the offending program text is known)."""

from __future__ import annotations

from goalagent.ast import Pos
from goalagent.kb.terms import Term


class KBError(Exception):
    """Base of every error raised by goalagent.kb (user-facing, with a readable message);
    ``pos`` is the source position of the offending program text, when known."""

    def __init__(self, message: str, pos: Pos | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.pos = pos


class PrologSyntaxError(KBError):
    """SWI-Prolog's reader rejected a text; ``offset`` is the 0-based offending character."""

    def __init__(self, message: str, offset: int) -> None:
        super().__init__(message)
        self.offset = offset

    def __str__(self) -> str:
        return f"{self.message} (at character {self.offset})"


class PrologRuntimeError(KBError):
    """A Prolog goal raised an exception; ``message`` is SWI's own wording, one line."""

    def __init__(self, message: str, term: Term | None = None) -> None:
        super().__init__(message)
        self.term = term


class LimitError(KBError):
    """An agent passed one of its bounds (goalagent.kb.limits) in a way that stops it."""


class Interrupted(BaseException):  # noqa: N818 - it is not an error but a stop
    """A signal (Ctrl-C, SIGTERM) aborted the running Prolog query (see goalagent.kb.watchdog).
    A BaseException, like KeyboardInterrupt: code that handles an agent's errors lets it
    through, so the run stops instead of one agent failing."""
