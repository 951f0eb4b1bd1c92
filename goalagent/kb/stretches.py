"""Where the main thread is, as the watchdog and the run's signal handler see it: in Python,
or in a *stretch* of Prolog (a query, or Prolog again after a callback into Python), how
deeply queries nest, whether a call into SWI-Prolog is half done, and the stop a signal left
for when it is not.

The watchdog (goalagent.kb.watchdog) bounds stretches and interrupts them; the run's signal
handler (goalagent.runner) raises its stop only when no call is in progress, and otherwise
leaves it here. :class:`~goalagent.kb.calls.PrologCalls` keeps the account as it calls.
"""

from __future__ import annotations

from time import monotonic

from goalagent.kb.errors import Interrupted, PrologRuntimeError
from goalagent.kb.terms import Atom

__all__ = ["Stretches"]


class Stretches:
    """The main thread's account of its stretches in Prolog and the stop pending for it."""

    def __init__(self) -> None:
        # The current stretch: its number and since when (None: in Python).
        self.stretch = 0
        self.stretch_since: float | None = None
        self.abort_reason: str | None = None  # why the watchdog aborted the running query
        self.depth = 0  # queries open (a callback into Python can open more)
        self.query = 0  # the number of the outermost query (the watchdog's memory watch)
        # A stop a signal asked for while queries were open: raised when they are all closed
        # (raising inside a callback would leave Prolog in between; see kb.watchdog).
        self.pending_stop: BaseException | None = None
        # Calls into SWI-Prolog in progress, from their first C call (opening a frame) to
        # their last (discarding it): a signal's stop raised in between would leave a query
        # open or a frame undiscarded, and the next query then runs on a broken engine. The
        # run's signal handler leaves its stop in pending_stop while this is not 0.
        self.guarded = 0

    def _enter(self) -> float | None:
        """A query opens: a new stretch in Prolog (see goalagent.kb.watchdog); returns the
        enclosing one's start, for :meth:`_leave`."""
        outer_since = self.stretch_since
        if not self.depth:
            self.query += 1
        self.depth += 1
        self.stretch += 1
        self.stretch_since = monotonic()
        return outer_since

    def _leave(self, outer_since: float | None) -> None:
        """The query has closed: the enclosing stretch, if any, runs again."""
        self.stretch_since = outer_since
        self.depth -= 1

    def _stop_if_asked(self) -> None:
        """A signal that came while Prolog ran: once back in Python, the stop it asked for."""
        if self.pending_stop is not None and self.depth == 0 and self.guarded == 0:
            stop, self.pending_stop = self.pending_stop, None
            raise stop

    def _aborted(self) -> BaseException:
        """The Python exception for a query the watchdog aborted: an interrupt (Ctrl-C,
        SIGTERM) stops the run; a query that outlived its time limit twice is the error
        of the agent that ran it."""
        reason, self.abort_reason = self.abort_reason, None
        if reason is None or reason.startswith("signal"):
            return Interrupted(reason or "aborted")
        return PrologRuntimeError(reason, Atom("$aborted"))
