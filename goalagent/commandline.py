"""How the ``goalagent`` command line reads and shows its options, for every command (the
language's and those extensions add): ``-h`` as well as ``--help``, readable metavars
(``--env NAME``, ``--env-param KEY=VALUE`` rather than Typer's ``<str>``, ``<list[str]>``),
and ``run --trace`` whose value may be left out or given after a space.

Typer builds the click command; this module only adjusts it (metavars) or its parsing
(``--trace``), because Typer has no option whose value is optional.
"""

from __future__ import annotations

from typing import Any

import typer
from typer.core import TyperArgument, TyperCommand

from goalagent.trace import IDLE, KINDS

HELP_OPTIONS = {"help_option_names": ["-h", "--help"]}
"""Context settings of the ``goalagent`` app: inherited by every command under it."""

METAVARS = {
    "env": "NAME", "env_param": "KEY=VALUE", "max_cycles": "N", "seed": "N", "trace": "KINDS",
    "trace_file": "FILE", "load_beliefs": "FILE", "save_beliefs": "FILE",
    "save_predicate": "NAME/ARITY", "save_every": "N|Ns|Nm|end", "breakpoint": "FILE:LINE|COND",
    "port": "N", "host": "ADDRESS", "max_inferences": "N", "max_query_seconds": "SECONDS",
    "max_beliefs": "N", "max_memory": "MB", "max_module_depth": "N", "plot": "FILE",
    "path": "PATH", "paths": "PATH",
}
"""Metavars of the options whose name alone would not say what they take; any other option
shows its name in capitals (``--out OUT``), a flag shows none."""


class _NamedArgument(TyperArgument):
    """An argument shown by its metavar alone (``PATH``): Typer would add its type beside it
    (``PATH <path>``)."""

    def display_type_rich(self, ctx: Any) -> str | None:
        return None


def readable_metavars(command: Any) -> None:
    """Give every option and argument of ``command`` and its subcommands a metavar people
    read (see ``METAVARS``), where none was chosen."""
    for param in getattr(command, "params", []):
        if param.name is None:
            continue
        if isinstance(param, TyperArgument):
            param.__class__ = _NamedArgument  # (the same argument, shown without its type)
        if param.metavar is not None:
            continue
        if getattr(param, "is_flag", False) or getattr(param, "count", False):
            param.metavar = ""
        else:
            param.metavar = METAVARS.get(param.name, param.name.upper())
    for sub in getattr(command, "commands", {}).values():
        readable_metavars(sub)


def _is_kinds(text: str) -> bool:
    """Whether ``text`` is a list of trace kinds (``goals,beliefs``)."""
    names = [name.strip().lower() for name in text.split(",")]
    return all(name in KINDS or name in ("all", IDLE) for name in names)


class RunCommand(TyperCommand):
    """``run``, where ``--trace`` may stand alone (``--trace=all``: everything) or take its
    kinds after ``=`` or a space (``--trace goals,beliefs``); a word after it that is not a
    list of kinds (the agent file) is left to be what it is."""

    def parse_args(self, ctx: typer.Context, args: list[str]) -> list[str]:
        given: list[str] = []
        rest = list(args)
        while rest:
            arg = rest.pop(0)
            if arg == "--trace":
                kinds = rest.pop(0) if rest and _is_kinds(rest[0]) else "all"
                arg = f"--trace={kinds}"
            given.append(arg)
        return super().parse_args(ctx, given)
