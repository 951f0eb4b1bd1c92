"""The ``goalagent`` command's entry point: signals are handled from its first instant.

Importing the command line (typer, rich, lark, pyswip starting SWI-Prolog) takes a second or
more, and a command then reads its files and builds its system before ``goalagent run``
installs the run's own handlers (goalagent/runner.py: the final save, exit 130/143/129).
Until then, and in commands that have no handlers of their own, SIGINT, SIGTERM and SIGHUP
end the process at once with one line saying so and the signal's exit code (128 + N): no
silent death, no KeyboardInterrupt traceback. This module imports only the standard library
(and goalagent.swi, which does too), so the handlers are in place before anything slow is
imported.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
from types import FrameType

from goalagent.swi import SWIPrologMissing

HANDLED = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


_UNWRITABLE = (OSError, RuntimeError, ValueError)
"""A terminal that is gone (SIGHUP), a write this signal interrupted (a reentrant call), a
closed stream: nothing more can be said there."""


def _stop(signum: int, frame: FrameType | None) -> None:
    """Flush what the command printed, say which signal stopped it, end with its code."""
    with contextlib.suppress(*_UNWRITABLE):
        sys.stdout.flush()
    with contextlib.suppress(*_UNWRITABLE):
        sys.stderr.write(f"goalagent: stopped by {signal.Signals(signum).name}\n")
        sys.stderr.flush()
    os._exit(128 + signum)


def _drop_output_that_cannot_be_written() -> None:
    """Flush stdout and stderr; one that cannot be written (the terminal closed: SIGHUP, or
    a closed pipe) is pointed at /dev/null, so that Python's own flush at exit does not
    turn the command's exit code into 120."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, stream.fileno())
            os.close(devnull)


def main() -> None:
    """Install the handlers, then run the command line (one line and exit 2 when there is
    no SWI-Prolog it can run on)."""
    for signum in HANDLED:
        signal.signal(signum, _stop)
    try:
        try:
            from goalagent.cli import main as command_line
        except SWIPrologMissing as missing:
            sys.stderr.write(f"error: {missing}\n")
            sys.exit(2)
        command_line()
    finally:
        _drop_output_that_cannot_be_written()
