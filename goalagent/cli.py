"""The ``goalagent`` command: run agents and multi-agent systems, check programs.

User mistakes (a malformed file, an unknown environment, a bad parameter) print one
``file:line:col: message`` line on stderr and exit with code 2, never a traceback.
"""

from __future__ import annotations

import contextlib
from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console
from rich.table import Table

from goalagent.affordance import (
    ReliabilityHistory,
    affordances,
    load_affordances,
    save_affordances,
)
from goalagent.agent import Agent, AgentError, validate_program
from goalagent.eis.exceptions import EnvironmentInterfaceException
from goalagent.kb.engine import KBError
from goalagent.kb.terms import Term
from goalagent.mas import MultiAgentSystem, parse_parameter
from goalagent.parser import GoalSyntaxError, parse_agent_file, parse_mas_file

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    help="Run GOAL agent programs whose beliefs live in SWI-Prolog.",
)
err_console = Console(stderr=True, highlight=False, soft_wrap=True)
USER_ERROR = 2


def _fail(message: str) -> typer.Exit:
    err_console.print(f"[bold red]error:[/] {message}", markup=True)
    return typer.Exit(code=USER_ERROR)


def _env_params(pairs: list[str]) -> dict[str, Term]:
    params: dict[str, Term] = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key.strip():
            raise _fail(f"--env-param {pair!r}: expected KEY=VALUE")
        params[key.strip()] = parse_parameter(value.strip())
    return params


class _TracePrinter:
    """Prints ``--trace`` events on stdout, one line each."""

    def __init__(self) -> None:
        self.console = Console(highlight=False, soft_wrap=True)

    def __call__(self, agent: str, kind: str, text: str) -> None:
        self.console.print(f"[dim]{agent}[/] [cyan]{kind:>12}[/] {text}", markup=True)


@app.command()
def run(
    path: Annotated[Path, typer.Argument(help="A .goal agent file or a .mas2g system file.")],
    env: Annotated[str | None, typer.Option(help="Environment name or module:Class.")] = None,
    env_param: Annotated[
        list[str] | None,
        typer.Option("--env-param", help="KEY=VALUE environment init parameter (Prolog term)."),
    ] = None,
    max_cycles: Annotated[int | None, typer.Option(help="Stop after this many cycles.")] = None,
    seed: Annotated[int, typer.Option(help="Seed for rule order and Prolog's random.")] = 0,
    trace: Annotated[bool, typer.Option(help="Show rules, bindings, actions per cycle.")] = False,
    load_beliefs: Annotated[
        Path | None, typer.Option(help="Prolog facts (e.g. saved afford/6) to add to the "
                                       "agents' beliefs before they start.")] = None,
    save_beliefs: Annotated[
        Path | None, typer.Option(help="Write the final afford/6 beliefs here.")] = None,
    plot: Annotated[
        Path | None, typer.Option(help="PNG of afford/6 reliabilities over the actions taken "
                                       "(default: afford-AGENT.png when agents have any).")
    ] = None,
) -> None:
    """Run an agent (or a multi-agent system) until it terminates or the cycle limit."""
    params = _env_params(env_param or [])
    options = dict(seed=seed, tracer=_TracePrinter() if trace else None,
                   warn=lambda message: err_console.print(message, markup=False))
    try:
        if path.suffix == ".mas2g":
            if env is not None:
                raise _fail("--env is for .goal files; a .mas2g names its own environment")
            system = MultiAgentSystem.from_mas_file(path, env_params=params, **options)
        else:
            if params and env is None:
                raise _fail("--env-param sets an environment's init parameters: give --env too")
            system = MultiAgentSystem.for_agent_file(path, environment=env, env_params=params,
                                                     **options)
        if load_beliefs is not None:
            for agent in system.agents:
                load_affordances(agent, load_beliefs)
    except (GoalSyntaxError, AgentError, KBError, EnvironmentInterfaceException) as err:
        raise _fail(str(err)) from None
    histories = {agent.name: ReliabilityHistory() for agent in system.agents}
    for agent in system.agents:
        histories[agent.name].record(agent)
    interrupted = False
    # A live status line on an interactive stderr (never with --trace, never in pipes).
    status = (err_console.status("starting") if err_console.is_terminal and not trace
              else contextlib.nullcontext())

    def after_cycle(agent: Agent) -> None:
        histories[agent.name].record(agent)
        if not isinstance(status, contextlib.nullcontext):
            status.update(f"{agent.name}: cycle {agent.cycle}, {agent.total_actions} actions")

    try:
        with status:
            system.run(max_cycles, after_cycle=after_cycle)
    except KeyboardInterrupt:  # Ctrl-C: stop, but keep what was learned and report it
        interrupted = True
        err_console.print("interrupted", markup=False)
    try:
        _report_affordances(system, histories, save_beliefs, plot)
        summaries = system.summaries()
    finally:
        system.close()
    for summary in summaries:
        err_console.print(str(summary), markup=False)
    if interrupted:
        raise typer.Exit(code=130)
    if any(summary.status == "failed" for summary in summaries):
        raise typer.Exit(code=1)


def _report_affordances(system: MultiAgentSystem, histories: dict[str, ReliabilityHistory],
                        save: Path | None, plot: Path | None) -> None:
    """The afford/6 table on stderr, the reliability plot, and the saved beliefs."""
    for agent in system.agents:
        rows = affordances(agent)
        if not rows:
            continue
        table = Table(title=f"afford/6 beliefs of {agent.name}")
        for column in ("Obj", "Act", "Eff", "Tot", "Suc", "Rel"):
            table.add_column(column, justify="right" if column in "TotSucRel" else "left")
        for row in rows:
            table.add_row(row.obj, row.act, row.eff, str(row.tot), str(row.suc),
                          f"{row.rel:.3f}")
        err_console.print(table)
        target = plot if plot is not None and len(system.agents) == 1 else (
            plot.with_name(f"{plot.stem}-{agent.name}{plot.suffix}") if plot is not None
            else Path(f"afford-{agent.name}.png"))
        histories[agent.name].plot(target, f"Affordance reliabilities of {agent.name}")
        err_console.print(f"reliability plot: {target}", markup=False)
    if save is not None:
        count = save_affordances(system.agents, save)
        err_console.print(f"saved {count} afford/6 beliefs to {save}", markup=False)


@app.command()
def check(
    paths: Annotated[list[Path], typer.Argument(help=".goal and .mas2g files to check.")],
) -> None:
    """Parse and validate programs: syntax, undefined actions and modules, macros; singleton
    variables are reported as warnings."""
    failed = False
    for path in paths:
        try:
            if path.suffix == ".mas2g":
                mas = parse_mas_file(path)
                programs = [parse_agent_file(path.parent / f.path) for f in mas.agentfiles]
            else:
                programs = [parse_agent_file(path)]
            for program in programs:
                validate_program(program)
                for warning in program.warnings:
                    err_console.print(warning, markup=False)
        except (GoalSyntaxError, AgentError) as err:
            err_console.print(str(err), markup=False)
            failed = True
            continue
        err_console.print(f"{path}: ok", markup=False)
    if failed:
        raise typer.Exit(code=USER_ERROR)


@app.command()
def snapshot(
    can: Annotated[str, typer.Option(help="Which garbage can: o1 .. o5.")] = "o1",
    out: Annotated[Path, typer.Option(help="Where to write the PNG.")] = Path("frame.png"),
    seed: Annotated[int, typer.Option(help="Scene seed.")] = 0,
    opening: Annotated[
        float | None, typer.Option(help="Open the can this far (metres) first.")] = None,
) -> None:
    """Render the head camera with each perceived part boxed and labelled and the measured
    opening written on the image."""
    from sim.scene import CANS
    from sim.snapshot import render_snapshot

    if can not in CANS:
        raise _fail(f"unknown can {can!r}; known cans: {', '.join(sorted(CANS))}")
    try:
        observation = render_snapshot(can, out, seed=seed, opening=opening)
    except ValueError as err:
        raise _fail(str(err)) from None
    parts = ", ".join(sorted(observation.parts))
    err_console.print(f"{out}: can {can}, parts {parts}, opening {observation.opening:.3f} m",
                      markup=False)
