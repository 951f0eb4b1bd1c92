"""The robot application's commands, added to ``goalagent`` through its extension seam.

Every command here exists twice: at the top level (``goalagent snapshot``, the spelling users
already know) and under ``goalagent robot`` (``goalagent robot snapshot``). A new command of the
robot application (``reproduce NAME``, ``objects list|show|forget``) is one more function in
``COMMANDS``; one that grows sub-commands of its own gets a Typer sub-app added in
``add_commands``. Heavy imports (MuJoCo, OpenCV) stay inside the command functions, so loading
this module for ``goalagent check`` costs nothing.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Annotated

import typer

from goalagent.console import err_console, user_error
from robot.objects import objects_app
from sim.headless import use_headless_rendering


def snapshot(
    can: Annotated[str, typer.Option(
        help="Which garbage can: o1 .. o5, slide, pedal, or a can file (.yaml).")] = "o1",
    out: Annotated[Path, typer.Option(help="Where to write the PNG.")] = Path("frame.png"),
    seed: Annotated[int, typer.Option(help="Scene seed.")] = 0,
    opening: Annotated[
        float | None, typer.Option(help="Open the can this far (metres) first.")] = None,
) -> None:
    """Render the head camera with each perceived part boxed and labelled and the measured
    opening written on the image."""
    use_headless_rendering()
    from robot.snapshot import render_snapshot
    from sim.canfile import CanFileError, find_can

    try:
        spec = find_can(can)
    except CanFileError as err:
        raise user_error(str(err)) from None
    try:
        observation = render_snapshot(spec, out, seed=seed, opening=opening)
    except ValueError as err:
        raise user_error(str(err)) from None
    parts = ", ".join(sorted(observation.parts))
    err_console.print(f"{out}: can {can}, parts {parts}, opening {observation.opening:.3f} m",
                      markup=False)


def reproduce(
    name: Annotated[str | None, typer.Argument(
        help="Which reproduction (see --list).", show_default=False)] = None,
    seeds: Annotated[int | None, typer.Option(
        help="Number of seeds, 0 .. K-1 (default: the reproduction's, 10; 2 with --quick)",
        show_default=False)] = None,
    out: Annotated[Path, typer.Option(
        help="Folder for NAME.json, NAME.md and the figures.")] = Path("results"),
    jobs: Annotated[int | None, typer.Option(
        help="Seeds run in parallel processes (default: the number of CPUs)",
        show_default=False)] = None,
    scale: Annotated[float, typer.Option(
        help="Run size in (0, 1]; 1 is the full size of the thesis's or paper's runs.")] = 1.0,
    quick: Annotated[bool, typer.Option(
        "--quick", help="A small run: the reproduction's quick scale (and 2 seeds).")] = False,
    list_: Annotated[bool, typer.Option(
        "--list", help="List the reproductions, one line each, and stop.")] = False,
    replot: Annotated[bool, typer.Option(
        "--replot", help="Redraw NAME.md and the figures from --out's NAME.json, run "
                         "nothing.")] = False,
) -> None:
    """Run a named reproduction of the thesis's results: seeds in parallel, then NAME.json
    (summary and per-seed numbers), NAME.md (measured beside the reference, with the gap) and
    PNG figures in --out."""
    import os

    from robot.reproduce.framework import UnknownReproduction, find, registered

    if list_:
        reproductions = registered()
        width = max((len(reproduction.name) for reproduction in reproductions), default=0)
        for reproduction in reproductions:
            err_console.print(f"{reproduction.name:<{width}}  {reproduction.description}",
                              markup=False)
        return
    if name is None:
        raise user_error("name a reproduction (goalagent reproduce --list shows them)")
    try:
        reproduction = find(name)
    except UnknownReproduction as err:
        raise user_error(str(err)) from None
    seeds = seeds if seeds is not None else 2 if quick else reproduction.default_seeds
    jobs = jobs if jobs is not None else os.cpu_count() or 1
    scale = reproduction.quick_scale if quick else scale
    if seeds < 1:
        raise user_error(f"--seeds must be at least 1, got {seeds}")
    if jobs < 1:
        raise user_error(f"--jobs must be at least 1, got {jobs}")
    if not 0.0 < scale <= 1.0:
        raise user_error(f"--scale must be in (0, 1], got {scale}")
    if out.exists() and not out.is_dir():
        raise user_error(f"--out {out} exists and is not a folder")
    _run_reproduction(reproduction, seeds, scale, jobs, out, replot)


def _run_reproduction(reproduction: object, seeds: int, scale: float, jobs: int,
                      out: Path, replot: bool) -> None:
    """Run it with a progress bar (or redraw it); print the table and where the files went."""
    from rich.table import Table

    from robot.reproduce import runner
    from robot.reproduce.report import gap_text, measured_text, number

    try:
        if replot:
            outcome = runner.replot(reproduction, out)
        else:
            outcome = runner.run(reproduction, seeds=seeds, scale=scale, jobs=jobs, out=out,
                                 console=err_console)
    except runner.ReproductionFailed as err:
        err_console.print(f"error: {err}", markup=False)
        raise typer.Exit(code=1) from None
    table = Table("quantity", "measured", "reference", "gap", "source")
    for row in outcome.comparisons:
        table.add_row(row.quantity, measured_text(row), number(row.reference), gap_text(row),
                      row.source or "—")
    err_console.print(table, markup=False)
    err_console.print("wrote " + ", ".join(str(path) for path in outcome.files), markup=False)


COMMANDS: tuple[Callable[..., None], ...] = (snapshot, reproduce)
"""The robot application's commands, in the order ``goalagent --help`` lists them."""


def add_commands(app: typer.Typer) -> None:
    """Add the robot commands to ``app``: each at the top level and under ``robot``."""
    robot = typer.Typer(name="robot", no_args_is_help=True,
                        help="The robot application: MuJoCo garbage cans, snapshots, "
                             "reproductions of the thesis's results.")
    for command in COMMANDS:
        app.command()(command)
        robot.command()(command)
    app.add_typer(objects_app())
    robot.add_typer(objects_app())
    app.add_typer(robot)
