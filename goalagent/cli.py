"""The ``goalagent`` command: run agents and multi-agent systems, check programs.

User mistakes (a malformed file, an unknown environment, a bad parameter) print one
``file:line:col: message`` line on stderr and exit with code 2, never a traceback.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console

from goalagent.agent import AgentError, validate_program
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
            system = MultiAgentSystem.for_agent_file(path, environment=env, env_params=params,
                                                     **options)
    except (GoalSyntaxError, AgentError, KBError, EnvironmentInterfaceException) as err:
        raise _fail(str(err)) from None
    try:
        summaries = system.run(max_cycles)
    finally:
        system.close()
    for summary in summaries:
        err_console.print(str(summary), markup=False)
    if any(summary.status == "failed" for summary in summaries):
        raise typer.Exit(code=1)


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
