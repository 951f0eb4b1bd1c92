"""MkDocs hook: the pages generated from the code when the site is built, so they cannot
drift from it.

- ``environments/reference.md``: every registered environment's init parameters (with the
  defaults its code reads them with), actions and first percepts
  (``goalagent.eis.reference``).
- ``cli.md``: every ``goalagent`` command's ``--help``, as the installed command prints it
  (the robot application's commands included).
"""

from __future__ import annotations

import contextlib
import io
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


def _help(command: object, args: list[str]) -> str:
    """What ``goalagent ARGS --help`` prints, 100 columns wide."""
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        try:
            command.main([*args, "--help"], prog_name="goalagent")  # type: ignore[attr-defined]
        except SystemExit:
            pass
    return out.getvalue().rstrip()


def _cli_page() -> str:
    """Every command's help text, the top level first."""
    from goalagent.cli import command

    os.environ["COLUMNS"] = "100"
    built = command()
    parts = [CLI_INTRO, "```text", _help(built, []), "```", ""]
    for name in built.commands:
        parts += [f"## `goalagent {name}`", "", "```text", _help(built, [name]), "```", ""]
    return "\n".join(parts)


def on_files(files: Files, config: MkDocsConfig) -> Files:
    """Add the generated pages to the site."""
    os.environ.setdefault("MUJOCO_GL", "egl")  # (the robot's environments render headless)
    from goalagent.eis.reference import reference

    files.append(File.generated(config, "environments/reference.md",
                                content=REFERENCE_INTRO + reference()))
    files.append(File.generated(config, "cli.md", content=_cli_page()))
    return files
