"""One ``goalagent run`` from start to exit code: run hooks, signals, the end-of-run order.

Ctrl-C (SIGINT), SIGTERM and SIGHUP (the terminal closed) stop the agents -- within a tick
of the watchdog even while a Prolog query runs away --, say which agent and rule were
running, and still finish the run: the hooks' ``finish`` -- ``--save-beliefs`` first, then
the reports -- and the summaries; the exit code is then 130, 143 or 129. A second signal
ends at once (whatever is being saved is abandoned, and since saves are atomic the previous
file stays whole). A run hook that raises is reported and the run goes on without it: an
extension's report never costs the user what the agents learned.
"""

from __future__ import annotations

import contextlib
import signal
from collections.abc import Callable, Iterator, Sequence
from types import FrameType
from typing import TYPE_CHECKING

from goalagent.extensions import RunContext, RunHook
from goalagent.kb.engine import get_engine
from goalagent.kb.errors import Interrupted
from goalagent.kb.rule_registry import aborted_rule
from goalagent.kb.watchdog import watchdog

if TYPE_CHECKING:
    from goalagent.agent import Agent
    from goalagent.mas import AgentSummary, MultiAgentSystem

EXIT_CODES = {signal.SIGINT: 130, signal.SIGTERM: 143, signal.SIGHUP: 129}


class RunStopped(KeyboardInterrupt):
    """A signal asked the run to stop (a KeyboardInterrupt, so that code catching Exception
    does not swallow it and code waiting for Ctrl-C, like the inspector's page after the
    agents ended, ends as it would on Ctrl-C)."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum
        self.exit_code = EXIT_CODES.get(signal.Signals(signum), 128 + signum)


@contextlib.contextmanager
def stop_on_signals() -> Iterator[list[int]]:
    """Within the block SIGINT, SIGTERM and SIGHUP raise :class:`RunStopped` (each time one
    comes), also while Prolog runs (the watchdog aborts the running query:
    goalagent.kb.watchdog); the previous handlers come back afterwards. Yields the signals
    received, in order (see :meth:`Run._after`)."""
    received: list[int] = []

    def handler(signum: int, frame: FrameType | None) -> None:
        received.append(signum)
        engine = get_engine()
        if engine.depth or engine.guarded:  # inside Prolog (or a callback from it): the
            # watchdog aborts the query; or between a call's first and last C call: the
            # stop comes when the call has ended (raised here it would leave it half done)
            engine.pending_stop = RunStopped(signum)
            return
        raise RunStopped(signum)

    def exit_code(signum: int) -> int:
        return EXIT_CODES.get(signal.Signals(signum), 128 + signum)

    previous = {signum: signal.signal(signum, handler) for signum in EXIT_CODES}
    try:
        with watchdog().watching_signals(exit_code):
            yield received
    finally:
        for signum, old in previous.items():
            signal.signal(signum, old)


def _stopped(error: BaseException) -> RunStopped:
    """A signal's stop, whether Python's handler or the watchdog's abort came first (the
    other one is then forgotten: it is the same stop)."""
    engine = get_engine()
    watchdog().stop_handled()
    pending, engine.pending_stop = engine.pending_stop, None
    if isinstance(error, RunStopped):
        return error
    if isinstance(pending, RunStopped):
        return pending
    signals = watchdog().signals
    return RunStopped(signals[-1] if signals else signal.SIGINT)


class Run:
    """A built system, its hooks and where to report: :meth:`execute` runs it to the end."""

    def __init__(self, system: MultiAgentSystem, hooks: Sequence[RunHook],
                 context: RunContext, report: Callable[[str], None]) -> None:
        self.system = system
        self.hooks = list(hooks)  # in order: --save-beliefs first, then the extensions'
        self.context = context
        self._report = report  # one line on stderr (user data: never markup)
        self.failed_hooks = 0
        self._cycling = list(self.hooks)  # hooks still called after each cycle
        self._last: Agent | None = None  # the agent whose cycle ended last
        self._signals: list[int] = []  # received while the run goes (see stop_on_signals)

    def report(self, line: str) -> None:
        """Say ``line`` on stderr; a terminal that is gone (SIGHUP: writes fail) or a closed
        pipe must not keep the run from its end (the saves)."""
        with contextlib.suppress(OSError):
            self._report(line)

    def execute(self, max_cycles: int | None,
                status: Callable[[Agent], None] | None = None) -> int:
        """Runs the system and finishes the run; returns the exit code (0, 1 when an agent
        or a hook failed, 130/143 when a signal stopped it)."""
        with stop_on_signals() as self._signals:
            try:
                return self._execute(max_cycles, status)
            except (RunStopped, Interrupted) as error:  # a second signal while finishing
                stop = _stopped(error)
                self.report(f"{stop}: stopped at once; what was being saved or reported is "
                            "left as it was")
                return stop.exit_code
            finally:
                with contextlib.suppress(RunStopped, Interrupted):
                    self.system.close()

    def _execute(self, max_cycles: int | None,
                 status: Callable[[Agent], None] | None) -> int:
        """Start hooks, cycles until the end or a signal, finish hooks, summaries."""
        stopped: RunStopped | None = None
        try:
            for hook in self.hooks:
                self._call(hook, "start")
            self.system.run(max_cycles, after_cycle=lambda agent: self._after(agent, status))
        except (RunStopped, Interrupted) as error:
            stopped = _stopped(error)
            self.system.interrupted = True
            self.report(self._stop_message(stopped))
        for hook in self.hooks:
            self._call(hook, "finish")
        summaries: list[AgentSummary] = self.system.summaries()
        for summary in summaries:
            self.report(str(summary))
        if stopped is not None:
            return stopped.exit_code
        failed = any(summary.status == "failed" for summary in summaries)
        return 1 if failed or self.failed_hooks else 0

    def _after(self, agent: Agent, status: Callable[[Agent], None] | None) -> None:
        """After each cycle: the hooks (one that raises is dropped, said once), the status.
        A signal received while the agents run is a stop that should not have got this far:
        its handler's exception was lost where Python drops exceptions (in ``__del__``, which
        a handler may interrupt): the stop comes here, one cycle late."""
        if self._signals:
            raise RunStopped(self._signals[-1])
        self._last = agent
        for hook in list(self._cycling):
            if not self._call(hook, "after_cycle", agent):
                self._cycling.remove(hook)
        if status is not None:
            status(agent)

    def _call(self, hook: RunHook, stage: str, *args: object) -> bool:
        """Calls ``hook.stage(context, *args)``; an exception is reported, not raised."""
        try:
            getattr(hook, stage)(self.context, *args)
        except Exception as error:  # noqa: BLE001 - any failure of a hook is reported
            self.failed_hooks += 1
            reason = getattr(error, "strerror", None) or error
            self.report(f"error: run hook {type(hook).__name__} failed at {stage}: "
                        f"{type(error).__name__}: {reason}")
            return False
        return True

    def _stop_message(self, stop: RunStopped) -> str:
        """``interrupted (SIGINT) in agent NAME, cycle N``: what was running (or the cycle
        that had just ended)."""
        agent = self.system.current
        rule = aborted_rule(get_engine())
        if agent is not None:
            where = f" in agent {agent.name}, cycle {agent.cycle}"
            if rule is not None:
                where += f", module {rule.shown}, rule at {rule.rule.pos}"
        elif self._last is not None:
            where = f" after agent {self._last.name}'s cycle {self._last.cycle}"
        else:
            where = ""
        return f"interrupted ({stop}){where}: stopping, finishing the run"
