"""The afford/6 report of ``goalagent run``: a table per agent and a reliability plot.

A run hook (``goalagent.extensions.RunHook``) of the robot extension: it records every
agent's reliabilities after each cycle and, when the run ends, prints the ``afford/6`` table
of each agent that has any on stderr and writes its reliability plot (``--plot FILE``, with
``-AGENT`` added when several agents report). Without ``--plot`` the plot goes beside the
``--save-beliefs`` file (the run's output folder) or else into a fresh temporary folder, as
``afford-AGENT.png``: a run never litters the current directory.
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import TYPE_CHECKING

from rich.markup import escape
from rich.table import Table

from goalagent.extensions import RunContext, RunHook, RunOption
from robot.affordance import ReliabilityHistory, affordances

if TYPE_CHECKING:
    from goalagent.agent import Agent

PLOT_OPTION = RunOption(
    "plot", Path, "PNG of afford/6 reliabilities over the actions taken "
                  "(default: afford-AGENT.png beside --save-beliefs, else in a "
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
        """The afford/6 table on stderr and the reliability plot of each agent with any."""
        agents = run.system.agents
        folder: Path | None = None  # the temporary folder, made when first needed
        for agent in agents:
            rows = affordances(agent)
            if not rows:
                continue
            table = Table(title=escape(f"afford/6 beliefs of {agent.name}"))
            for column in ("Obj", "Act", "Eff", "Tot", "Suc", "Rel"):
                table.add_column(column, justify="right" if column in "TotSucRel" else "left")
            for row in rows:
                table.add_row(escape(row.obj), escape(row.act), escape(row.eff), str(row.tot),
                              str(row.suc), f"{row.rel:.3f}")
            run.console.print(table)
            target = plot_path(run, agent.name, several=len(agents) > 1)
            if target is None:
                folder = folder or Path(tempfile.mkdtemp(prefix="goalagent-plots-"))
                target = folder / f"afford-{agent.name}.png"
            self.histories[agent.name].plot(target, f"Affordance reliabilities of {agent.name}")
            run.console.print(f"reliability plot: {target}", markup=False)


def plot_path(run: RunContext, agent: str, *, several: bool) -> Path | None:
    """Where ``agent``'s reliability plot goes: ``--plot`` (``-AGENT`` added when
    ``several`` agents report), else ``afford-AGENT.png`` beside ``--save-beliefs``; None
    without either (the caller makes a temporary folder and prints the path)."""
    plot: Path | None = run.options.get("plot")  # type: ignore[assignment]
    if plot is not None:
        return plot.with_name(f"{plot.stem}-{agent}{plot.suffix}") if several else plot
    saved: Path | None = run.options.get("save_beliefs")  # type: ignore[assignment]
    return saved.parent / f"afford-{agent}.png" if saved is not None else None
