"""MkDocs hook: the pages generated from the code when the site is built, so they cannot
drift from it.

- ``environments/reference.md``: every registered environment's init parameters (with the
  defaults its code reads them with), actions and first percepts
  (``goalagent.eis.reference``).
- ``cli.md``: every ``goalagent`` command's ``--help``, as the installed command prints it
  (the robot application's commands included).
"""

from __future__ import annotations

import os

from mkdocs.config.defaults import MkDocsConfig
from mkdocs.structure.files import File, Files

REFERENCE_INTRO = """# Environments: the reference

Generated from the code when this site is built (`goalagent.eis.reference`): the init
parameters each environment declares, with the defaults its code reads them with; its actions
with their parameters as its Python methods take them, and what each does; the entities and
the percepts an agent gets in its first cycle when the environment starts with its default
init parameters. What the percepts mean, which come once or on change, and the worlds behind
them: [GOAL's environments](goal-environments.md), [the robot's](robot-environments.md).

"""

CLI_INTRO = """# The command line

`goalagent COMMAND --help` prints what follows (generated from the command itself when this
site is built). Shell completion: `goalagent --install-completion` (bash, zsh, fish,
PowerShell), or `goalagent --show-completion` to see the script.

"""


def _cli_page() -> str:
    """Every command's help text, the top level first."""
    from typer.testing import CliRunner

    from goalagent.cli import create_app

    app = create_app()
    runner = CliRunner()
    environment = {"COLUMNS": "100", "TERM": "dumb", "NO_COLOR": "1"}
    top = runner.invoke(app, ["--help"], env=environment, prog_name="goalagent")
    names = [command.name for command in app.registered_commands if command.name]
    names += [group.name for group in app.registered_groups if group.name]
    parts = [CLI_INTRO, "```text", top.output.rstrip(), "```", ""]
    for name in names:
        result = runner.invoke(app, [name, "--help"], env=environment, prog_name="goalagent")
        parts += [f"## `goalagent {name}`", "", "```text", result.output.rstrip(), "```", ""]
    return "\n".join(parts)


def on_files(files: Files, config: MkDocsConfig) -> Files:
    """Add the generated pages to the site."""
    os.environ.setdefault("MUJOCO_GL", "egl")  # (the robot's environments render headless)
    from goalagent.eis.reference import reference

    files.append(File.generated(config, "environments/reference.md",
                                content=REFERENCE_INTRO + reference()))
    files.append(File.generated(config, "cli.md", content=_cli_page()))
    return files
