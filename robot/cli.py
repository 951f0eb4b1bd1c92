"""The robot application's commands, added to ``goalagent`` through its extension seam.

Every command here exists twice: at the top level (``goalagent snapshot``, the spelling users
already know) and under ``goalagent robot`` (``goalagent robot snapshot``). A new command of the
robot application (``objects list|show|forget``) is one more function in
``COMMANDS``; one that grows sub-commands of its own gets a Typer sub-app added in
``add_commands``. ``reproduce`` and ``sweep`` are the research workbench's
(``robot/reproduce/commands.py``). Heavy imports (MuJoCo, OpenCV) stay inside the
command functions, so loading this module for ``goalagent check`` costs nothing.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Annotated

import typer

from goalagent.console import err_console, user_error
from robot.objects import objects_app
from robot.reproduce.commands import reproduce, sweep
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


COMMANDS: tuple[Callable[..., None], ...] = (snapshot, reproduce, sweep)
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
