"""The afford/6 report of ``goalagent run``: a table per agent and a reliability plot.

A run hook (``goalagent.extensions.RunHook``) of the robot extension: it records every
agent's reliabilities after each cycle and, when the run ends, prints the ``afford/6`` table
of each agent that has any on stderr and writes its reliability plot (``--plot FILE``, with
``-AGENT`` added when several agents report). Without ``--plot`` the plot goes beside the
``--save-beliefs`` file STEM.pl (the run's output folder) as ``STEM-afford-AGENT.png``, so
two runs saving in one folder keep their own, or else into a fresh temporary folder as
``afford-AGENT.png``: a run never litters the current directory.
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import TYPE_CHECKING

from rich.markup import escape
from rich.table import Table

from goalagent.extensions import RunContext, RunHook, RunOption
from robot.affordance import ReliabilityHistory, affordances, count_affordances

if TYPE_CHECKING:
    from goalagent.agent import Agent

MAX_ROWS = 50
"""The most rows of an agent's afford/6 table printed at the end of a run (all of them go
to ``--save-beliefs``)."""

PLOT_OPTION = RunOption(
    "plot", Path, "PNG of afford/6 reliabilities over the actions taken "
                  "(default: STEM-afford-AGENT.png beside --save-beliefs STEM.pl, else in a "
                  "temporary folder; printed when written).")


class AffordanceReport(RunHook):
    """Reliability histories during the run; the afford/6 tables and plots at its end."""

    def __init__(self) -> None:
        self.histories: dict[str, ReliabilityHistory] = {}

    def start(self, run: RunContext) -> None:
        """Record where every agent starts (after --load-beliefs)."""
        for agent in run.system.agents:
            self.histories[agent.name] = ReliabilityHistory()
            self.histories[agent.name].record(agent)

    def after_cycle(self, run: RunContext, agent: Agent) -> None:
        """Note the reliabilities that changed in this cycle."""
        self.histories[agent.name].record(agent)

    def finish(self, run: RunContext) -> None:
        """The afford/6 table on stderr (its first ``MAX_ROWS`` rows) and the reliability
        plot of each agent with any."""
        agents = run.system.agents
        folder: Path | None = None  # the temporary folder, made when first needed
        for agent in agents:
            history = self.histories.get(agent.name)
            rows = affordances(agent, limit=MAX_ROWS)
            if not rows:
                if history is not None:
                    history.close()
                continue
            total = count_affordances(agent)
            table = Table(title=escape(f"afford/6 beliefs of {agent.name}"),
                          caption=(f"the first {MAX_ROWS} of {total}" if total > len(rows)
                                   else None))
            for column in ("Obj", "Act", "Eff", "Tot", "Suc", "Rel"):
                table.add_column(column, justify="right" if column in "TotSucRel" else "left")
            for row in rows:
                table.add_row(escape(row.obj), escape(row.act), escape(row.eff), str(row.tot),
                              str(row.suc), f"{row.rel:.3f}")
            run.console.print(table)
            if history is None:
                continue
            history.close()
            target = plot_path(run, agent.name, several=len(agents) > 1)
            if target is None:
                folder = folder or Path(tempfile.mkdtemp(prefix="goalagent-plots-"))
                target = folder / f"afford-{agent.name}.png"
            try:
                history.plot(target, f"Affordance reliabilities of {agent.name}")
            except OSError as error:
                run.console.print(f"warning: cannot write the reliability plot {target}: "
                                  f"{error.strerror or error}", markup=False)
                continue
            run.console.print(f"reliability plot: {target}", markup=False)


def plot_path(run: RunContext, agent: str, *, several: bool) -> Path | None:
    """Where ``agent``'s reliability plot goes: ``--plot`` (``-AGENT`` added when
    ``several`` agents report), else ``STEM-afford-AGENT.png`` beside the ``--save-beliefs``
    file STEM.pl (so two runs saving in one folder keep their own plots); None without
    either (the caller makes a temporary folder and prints the path)."""
    plot: Path | None = run.options.get("plot")  # type: ignore[assignment]
    if plot is not None:
        return plot.with_name(f"{plot.stem}-{agent}{plot.suffix}") if several else plot
    saved: Path | None = run.options.get("save_beliefs")  # type: ignore[assignment]
    return saved.parent / f"{saved.stem}-afford-{agent}.png" if saved is not None else None
