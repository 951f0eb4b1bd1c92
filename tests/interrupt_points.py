"""Raising a signal's stop at every point a Python signal handler could: Python runs a handler
between any two bytecodes of the main thread, so a handler that raises (the run's Ctrl-C)
can land between any two of them. :func:`interrupt_at` raises at the N-th opcode executed in
the given files; a test walks N over all of them."""

from __future__ import annotations

import contextlib
import sys
from collections.abc import Callable, Iterator
from types import FrameType
from typing import Any


class Stop(KeyboardInterrupt):
    """The stop raised at an interrupt point (a KeyboardInterrupt, like the run's)."""


@contextlib.contextmanager
def interrupt_at(point: int, files: tuple[str, ...],
                 allowed: Callable[[], bool] = lambda: True) -> Iterator[list[int]]:
    """Within the block, raise :class:`Stop` at the ``point``-th opcode run in a frame of one
    of ``files`` at which ``allowed()`` holds (the handler's own condition for raising). The
    yielded list gets the number of such opcodes seen (to know when ``point`` is past the
    end)."""
    seen = [0]

    def opcodes(frame: FrameType, event: str, arg: Any) -> Any:
        if event == "opcode" and allowed():
            seen[0] += 1
            if seen[0] == point:
                raise Stop(f"interrupt point {point}")
        return opcodes

    def calls(frame: FrameType, event: str, arg: Any) -> Any:
        # Not in __del__: Python drops an exception raised there (the run's after-cycle check
        # catches a stop lost that way: goalagent/runner.py, Run._after).
        if frame.f_code.co_filename.endswith(files) and frame.f_code.co_name != "__del__":
            frame.f_trace_opcodes = True
            return opcodes
        return None

    previous = sys.gettrace()
    sys.settrace(calls)
    try:
        yield seen
    finally:
        sys.settrace(previous)
