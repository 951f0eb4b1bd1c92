"""A thread that bounds what the main thread's Prolog does: wall-clock time per stretch,
memory per agent, and Ctrl-C / SIGTERM while a query runs.

Python runs a signal handler only between bytecodes, so while the main thread is inside a
Prolog query (ctypes releases the GIL) Ctrl-C would wait for the query to end -- for ever,
if it runs away. The engine notes each *stretch* the main thread spends in Prolog (a query,
or Prolog again after a callback into Python: ``Engine.stretch`` / ``stretch_since``). This
daemon thread reads the signals Python's C-level handler writes
to a wakeup pipe, and checks the running stretch every ``TICK`` seconds:

- a stretch older than the time limit gets ``ga_limit(time(T))`` thrown in it (the rule it
  is in is not applicable, with a warning); if the agent's code catches that and runs on,
  the next time it is aborted (``'$aborted'`` cannot be swallowed) and the agent stopped;
- a signal aborts the running stretch (the run then stops as Ctrl-C says); a second signal
  that has not ended the process within a second ends it at once, and so does the first
  when the stretch has not ended ``STOP_GRACE`` seconds after its abort (a built-in that
  does not look at signals: saves are atomic, the last one stays);
- the process's resident memory, read every tick (a few microseconds, off the main thread):
  when the running query of an agent has grown it by more than the agent's --max-memory,
  the query is asked to account for it (memory.pl: it stops the agent if what is not
  Prolog's stacks passes the budget); when the process has grown past its alarm mark (the
  larger of an eighth of its size and 64 MB; the smallest budget of an agent made where
  that is less), the running agent accounts for what it holds at once and
  every agent at its next call (``generation``; goalagent/kb/memory.py); a call that has
  grown it past four budgets and Prolog's stacks without returning to Prolog is in a
  built-in nothing can interrupt: the process ends then, before the machine runs out of
  memory.

Both use ``thread_signal/2`` from the watchdog's engine; the goal it sends checks that the
same stretch is still running (its number), so nothing strays into a later query. Why a
thread of our own: SWI's ``call_with_time_limit/2`` would time Python callbacks (physics,
rendering) too, and cost an alarm per call; this costs two clock reads per query.
"""

from __future__ import annotations

import contextlib
import os
import select
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator

from goalagent.kb.calls import define_foreign
from goalagent.kb.clib import (
    PL_call,
    PL_chars_to_term,
    PL_discard_foreign_frame,
    PL_new_term_ref,
    PL_open_foreign_frame,
    PL_thread_attach_engine,
    PL_thread_destroy_engine,
)
from goalagent.kb.engine import Engine, get_engine

__all__ = ["TICK", "Watchdog", "watchdog"]

TICK = 0.05  # seconds between looks at the running stretch
ALARM_STEP = 64 * 2**20  # resident growth (bytes) between memory alarms, at least
STACK_LIMIT = 2**30  # SWI-Prolog's default stack_limit: what a query's stacks may take
_PAGE = os.sysconf("SC_PAGE_SIZE")
WAKE = signal.SIGUSR2  # sent to the main thread after a Prolog signal, to end a sleep
HARD_EXIT_AFTER = 1.0  # a second signal ends the process if this much later it still runs
STOP_GRACE = 5.0  # a signal's abort not taken after this many seconds ends the process


class Watchdog:
    """The process's watchdog (see :func:`watchdog`); ``time_limit`` is the running agent's
    ``--max-query-seconds`` (None: no limit)."""

    def __init__(self, engine: Engine) -> None:
        self.engine = engine
        self.time_limit: float | None = None
        self.signals: list[int] = []  # signals received while watching them
        self._read, self._write = os.pipe()
        os.set_blocking(self._read, False)
        os.set_blocking(self._write, False)
        self._struck: int | None = None  # the stretch a time limit was thrown in
        self._struck_at = 0.0  # when (the next strike comes one limit later)
        self._stopping: int | None = None  # a signal asking to stop, not yet done
        self._aborted: int | None = None  # the stretch last aborted for it, and when
        self._aborted_at = 0.0
        self._exit_code: Callable[[int], int] = lambda signum: 128 + signum
        # The running agent's belief module, memory budget in bytes and name (set before
        # each of its calls), and the memory watch (see _check_memory).
        self.running: tuple[str, int, str] | None = None
        self.generation = 0  # memory alarms so far: each agent accounts once per alarm
        self._statm = os.open("/proc/self/statm", os.O_RDONLY)
        self._last_rss = self._resident()
        self._mark = self._last_rss + ALARM_STEP
        self._query = 0  # the outermost query watched, the memory when it began, and how
        self._query_base = 0  # much growth asks it for an account next
        self._next_ask = 0
        self._smallest_budget: int | None = None  # of an agent made (note_budget)
        # Taken to read the signals' pipe and act on them, and by stop_handled(): a signal
        # Python has already turned into the run's stop is never acted on again later.
        self._lock = threading.Lock()
        # The running stretch's number, -1 when none runs (a signal that arrives after the
        # query ended, e.g. handled as the process exits, then does nothing).
        define_foreign(engine, "ga_guard", "$ga_stretch",
                       lambda _: engine.stretch if engine.stretch_since is not None else -1,
                       stretch=False)
        self._main = threading.main_thread().ident
        if threading.get_ident() == self._main and signal.getsignal(WAKE) in (
                signal.SIG_DFL, signal.SIG_IGN, None):
            signal.signal(WAKE, lambda signum, frame: None)  # only to interrupt a sleep
        threading.Thread(target=self._watch, name="goalagent-watchdog", daemon=True).start()

    @contextlib.contextmanager
    def watching_signals(self, exit_code: Callable[[int], int]) -> Iterator[None]:
        """Within the block, signals also reach the watchdog (Python's handlers still run
        as installed); ``exit_code`` gives the code of a hard exit. Main thread only."""
        self.signals.clear()
        self._exit_code = exit_code
        previous = signal.set_wakeup_fd(self._write, warn_on_full_buffer=False)
        try:
            yield
        finally:
            signal.set_wakeup_fd(previous)

    def stop_handled(self) -> None:
        """Python has taken the stop a signal asked for: later queries (finishing the run)
        are not aborted for it, nor for a signal of that stop the watchdog has not read
        yet (its byte is in the pipe before Python's handler runs: it is read here)."""
        with self._lock:
            for signum in self._pending():
                self._count(signum)
            self._stopping = None

    # ------------------------------------------------------------------ the thread

    def _watch(self) -> None:
        while True:
            ready, _, _ = select.select([self._read], [], [], TICK)
            with self._lock:
                if ready:
                    for signum in self._pending():
                        self._signal(signum)
                self._check_stop()
            self._check_time()
            self._check_memory()

    def _pending(self) -> list[int]:
        """The signals written to the pipe and not read yet (without our own wake-ups)."""
        with contextlib.suppress(BlockingIOError):
            return [byte for byte in os.read(self._read, 64) if byte != WAKE]
        return []

    def _count(self, signum: int) -> None:
        """Notes a signal; a second one ends the process if it is still here a second later."""
        self.signals.append(signum)
        if len(self.signals) >= 2:
            threading.Timer(HARD_EXIT_AFTER, self._hard_exit, (signum,)).start()

    def _signal(self, signum: int) -> None:
        """A signal arrived: abort the running query (now, or as soon as Prolog runs again
        if the main thread is in a callback, see :meth:`_check_stop`)."""
        self._count(signum)
        self._stopping = signum
        self._check_stop()

    def _check_stop(self) -> None:
        """While a stop is asked for and queries are open, abort each stretch once."""
        engine = self.engine
        if self._stopping is None:
            return
        if engine.depth == 0:
            self._stopping = None  # back in Python: its handler stops the run
        elif engine.stretch_since is not None and engine.stretch != self._aborted:
            self._aborted, self._aborted_at = engine.stretch, time.monotonic()
            self._send("abort", f"signal {signal.Signals(self._stopping).name}")
        elif (engine.stretch_since is not None and engine.stretch == self._aborted
              and time.monotonic() - self._aborted_at > STOP_GRACE):
            # One built-in call SWI-Prolog cannot interrupt (its writer, its reader, big
            # integers: sizes.pl bounds those it knows): the signal still ends the run.
            self._hard_exit(self._stopping, f": Prolog did not return within {STOP_GRACE:g} "
                            "s (a built-in that does not look at signals);")

    def _hard_exit(self, signum: int, why: str = " again:") -> None:
        sys.stderr.write(f"{signal.Signals(signum).name}{why} ending at once; the last save "
                         "is kept\n")
        sys.stderr.flush()
        os._exit(self._exit_code(signum))

    def _check_time(self) -> None:
        """Throw ``ga_limit(time(T))`` in a stretch older than the limit; abort it if it is
        still running one limit after that. Reads the engine's stretch, never writes it
        (the main thread may end the stretch at any moment: a time written back here could
        outlive it and strike a later, idle moment)."""
        engine = self.engine
        limit, since, stretch = self.time_limit, engine.stretch_since, engine.stretch
        if limit is None or since is None or engine.depth == 0:
            return
        struck = self._struck == stretch
        if time.monotonic() - (self._struck_at if struck else since) < limit:
            return
        if struck:
            self._send("abort", f"ran on for {2 * limit:g} s past its time limit of "
                       f"{limit:g} s (--max-query-seconds) although interrupted; stopped")
        else:
            self._struck = stretch
            self._send(f"time({limit!r})", None)
        self._struck_at = time.monotonic()  # the next strike after another limit

    def note_budget(self, limit: int) -> None:
        """An agent with a memory budget of ``limit`` bytes was made: the process's alarm
        comes at least every ``limit`` of growth, or an agent that holds a little more each
        call would be seen only once the process grew by ALARM_STEP, however many calls that
        took (a record a cycle with --max-memory 16 was stopped holding 220 MB)."""
        if self._smallest_budget is None or limit < self._smallest_budget:
            self._smallest_budget = limit

    def _resident(self) -> int:
        """The process's resident memory in bytes (/proc/self/statm: no lock, no walk)."""
        return int(os.pread(self._statm, 64, 0).split()[1]) * _PAGE

    def _check_memory(self) -> None:
        """The memory watch: growth of the running query past its agent's budget asks it
        for an account (again each quarter budget more); growth of the process past the
        alarm mark starts a new generation (every agent accounts at its next call) and asks
        the running agent at once. The mark follows the memory down (an agent stopped and
        its atoms collected), so a new hog is seen as soon."""
        engine, agent = self.engine, self.running
        rss = self._resident()
        running = bool(engine.depth) and engine.stretch_since is not None and agent is not None
        if running:
            module, limit, name = agent  # type: ignore[misc]
            if engine.query != self._query:  # first seen: it began after the last look
                self._query, self._query_base, self._next_ask = engine.query, self._last_rss, limit
            growth = rss - self._query_base
            if growth > self._next_ask:
                self._next_ask = growth + limit // 4
                base = self._query_base // _PAGE
                self._send(f"call_memory({module}, {limit}, {base}, {_PAGE})", None)
            if growth > 4 * limit + STACK_LIMIT:
                self._out_of_memory(name, growth)
        step = max(ALARM_STEP, rss // 8)
        if self._smallest_budget is not None:
            step = min(step, self._smallest_budget)
        next_mark = rss + step
        if rss > self._mark:
            self.generation += 1
            if running:
                self._send(f"held_memory({module}, {limit})", None)
            self._mark = next_mark
        else:
            self._mark = min(self._mark, next_mark)
        self._last_rss = rss

    def _out_of_memory(self, name: str, growth: int) -> None:
        """One call grew the process past four budgets and Prolog's stacks: it is in a
        built-in SWI-Prolog cannot interrupt (assertz/1 of a term whose subterms are
        shared 30 deep writes out 2^30 of them), and only ending the process now keeps
        the machine from running out of memory."""
        sys.stderr.write(f"error: agent {name}: one call took {growth >> 20:,} MB without "
                         "returning to Prolog (a built-in that cannot be interrupted): "
                         "ending the run at once; the last save is kept\n")
        sys.stderr.flush()
        os._exit(1)

    def _send(self, action: str, reason: str | None) -> None:
        """Asks the main thread's Prolog to do ``action`` in the running stretch, if any."""
        stretch = self.engine.stretch
        if self.engine.stretch_since is None:
            return  # the main thread is in Python: its own handler (if any) acts
        if reason is not None:
            self.engine.abort_reason = reason
        goal = f"thread_signal(main, ga_guard:stretch_signal({stretch}, {action}))".encode()
        if PL_thread_attach_engine(None) < 0:  # a Prolog engine only while it signals: one
            return  # left attached would keep SWI from cleaning up at exit
        try:
            frame = PL_open_foreign_frame()
            term = PL_new_term_ref()
            if PL_chars_to_term(goal, term):
                PL_call(term, None)
            PL_discard_foreign_frame(frame)
        finally:
            PL_thread_destroy_engine()
        if self._main is not None and signal.getsignal(WAKE) not in (signal.SIG_DFL,
                                                                      signal.SIG_IGN, None):
            # A blocking call (sleep/1, waiting for input) ends with EINTR and SWI then
            # handles the signal sent above (SWI's thread-alert handler for this signal is
            # replaced by ours, which only interrupts: see __init__ and clib.py).
            signal.pthread_kill(self._main, WAKE)


_watchdog: Watchdog | None = None
_lock = threading.Lock()


def watchdog() -> Watchdog:
    """The process's watchdog, started on first use."""
    global _watchdog
    with _lock:
        if _watchdog is None:
            _watchdog = Watchdog(get_engine())
        return _watchdog
