"""Extensions: how applications built on goalagent join its CLI and environment registry.

goalagent never imports an application. An installed package declares an entry point in the
group ``goalagent.extensions`` (``[project.entry-points."goalagent.extensions"]`` in its
``pyproject.toml``) naming an ``Extension``: environment names (imported only when an agent
asks for one), Prolog libraries agents ``#import`` by name, commands for the ``goalagent``
CLI, hooks that observe ``goalagent run`` (reports, plots, periodic saving) with the ``run``
options they read, and the predicates ``--save-beliefs`` writes. Entry points are read the
first time something asks for them, so an extension's heavy dependencies (MuJoCo, OpenCV)
load only when one of its environments or commands is used: the extension's own module must
stay light.
"""

from __future__ import annotations

import functools
import sys
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from importlib.metadata import entry_points
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import typer
    from rich.console import Console

    from goalagent.agent import Agent
    from goalagent.kb.terms import Term
    from goalagent.mas import MultiAgentSystem

ENTRY_POINT_GROUP = "goalagent.extensions"


@dataclass(frozen=True)
class SavedPredicate:
    """A predicate whose beliefs ``goalagent run --save-beliefs`` writes as Prolog facts.

    ``description`` heads the saved file (``% DESCRIPTION saved by goalagent``); ``canonical``
    may rewrite one belief's arguments before they are written (e.g. a reliability kept as the
    integer ``1`` written as ``1.0``), so saved files read the same whatever Prolog computed.
    ``checks`` are what ``--load-beliefs`` requires of such facts before anything runs: pairs
    of a Prolog condition over the variables of ``template`` (e.g. ``integer(Tot), Tot >=
    0`` for ``afford(Obj, Act, Eff, Tot, Suc, Rel)``) and its meaning in words, which the
    error at a failing fact's ``file:line:col`` quotes.
    """

    name: str
    arity: int
    description: str = ""
    canonical: Callable[[tuple[Term, ...]], tuple[Term, ...]] | None = None
    template: str = ""
    checks: Sequence[tuple[str, str]] = ()

    @property
    def indicator(self) -> str:
        """``name/arity``."""
        return f"{self.name}/{self.arity}"

    @property
    def heading(self) -> str:
        """What the saved file says these facts are."""
        return self.description or f"{self.indicator} beliefs"


@dataclass(frozen=True)
class RunOption:
    """An option an extension adds to ``goalagent run`` (``--name-with-dashes``); its value
    reaches every run hook as ``run.options[name]``."""

    name: str
    type: type
    help: str
    default: object = None


@dataclass
class RunContext:
    """What run hooks see: the running system, every ``run`` option's value, where to report."""

    system: MultiAgentSystem
    options: Mapping[str, object]
    console: Console  # stderr: reports go here, stdout belongs to the agents' print/1


class RunHook:
    """Observes one ``goalagent run``; override what you need.

    Order: ``start`` after the system is built and ``--load-beliefs`` is applied, before the
    first cycle; ``after_cycle`` after each cycle of each agent (e.g. saving every N cycles);
    ``finish`` after the last cycle, also when the run is interrupted (reports, plots, final
    saves). Hooks of extensions run in extension-name order, the language's own last.
    """

    def start(self, run: RunContext) -> None:
        """Before the first cycle."""

    def after_cycle(self, run: RunContext, agent: Agent) -> None:
        """After one cycle of ``agent``."""

    def finish(self, run: RunContext) -> None:
        """After the run."""


@dataclass(frozen=True)
class PanelView:
    """What one inspector panel shows for one agent: a table (cells as plain text), a PNG
    image, a caption. Never markup: the page shows every string as text."""

    title: str
    columns: tuple[str, ...] = ()
    rows: tuple[tuple[str, ...], ...] = ()
    png: bytes | None = None
    caption: str = ""


class InspectorPanel:
    """A panel of ``goalagent run --inspect`` (the mind inspector): an application's view of
    an agent, asked for after the agent's cycles on the thread that runs the agents."""

    def view(self, run: RunContext, agent: Agent) -> PanelView | None:
        """What to show for ``agent`` now (None: nothing for this agent)."""
        return None


@dataclass(frozen=True)
class Extension:
    """What an application adds to goalagent (the object an entry point names).

    Attributes:
        name: shown in messages about the extension.
        environments: environment name -> ``package.module:Class``, imported on first use.
        prolog_libraries: Prolog files agents ``#import`` by their file name (``#import
            "affordance.pl".``) when no file of that name is next to the program.
        add_commands: called with the ``goalagent`` Typer app to add commands or sub-apps.
        run_options: options added to ``goalagent run`` for this extension's hooks.
        run_hooks: factories (e.g. RunHook subclasses) of the hooks observing each run.
        saved_predicates: what ``--save-beliefs`` writes (besides ``--save-predicate``).
        prepare: called once before the first of its environments is imported (e.g. to
            choose MuJoCo's headless renderer, which must happen before mujoco is imported).
        inspector_panels: factories of the panels the mind inspector (``--inspect``) adds.
    """

    name: str
    environments: Mapping[str, str] = field(default_factory=dict)
    prolog_libraries: Sequence[Path] = ()
    add_commands: Callable[[typer.Typer], None] | None = None
    run_options: Sequence[RunOption] = ()
    run_hooks: Sequence[Callable[[], RunHook]] = ()
    saved_predicates: Sequence[SavedPredicate] = ()
    prepare: Callable[[], None] | None = None
    inspector_panels: Sequence[Callable[[], InspectorPanel]] = ()

    def ensure_prepared(self) -> None:
        """Run ``prepare`` the first time it is asked for, never again."""
        if self.prepare is not None and self.name not in _PREPARED:
            _PREPARED.add(self.name)
            self.prepare()


_PREPARED: set[str] = set()


@functools.cache
def installed_extensions() -> tuple[Extension, ...]:
    """The extensions installed in this Python environment, by entry-point name.

    One that cannot be loaded is skipped with a warning on stderr (naming it and why), so a
    broken application never stops the language from running plain agents.
    """
    found: list[Extension] = []
    for point in sorted(entry_points(group=ENTRY_POINT_GROUP), key=lambda p: p.name):
        try:
            extension = point.load()
        except Exception as error:  # noqa: BLE001 - any failure of foreign code is reported
            _warn(f"goalagent extension {point.name!r} ({point.value}) could not be loaded: "
                  f"{type(error).__name__}: {error}")
            continue
        if not isinstance(extension, Extension):
            _warn(f"goalagent extension {point.name!r} ({point.value}) is not a "
                  "goalagent.extensions.Extension; skipped")
            continue
        found.append(extension)
    return tuple(found)


def saved_predicates() -> tuple[SavedPredicate, ...]:
    """Every predicate the installed extensions ask ``--save-beliefs`` to write."""
    return tuple(p for extension in installed_extensions() for p in extension.saved_predicates)


def prolog_library(name: str) -> Path | None:
    """The Prolog library file called ``name`` (e.g. ``affordance.pl``) that an installed
    extension brings (the first, in extension-name order), or None."""
    for extension in installed_extensions():
        for library in extension.prolog_libraries:
            if library.name == name:
                return library
    return None


def _warn(message: str) -> None:
    print(f"warning: {message}", file=sys.stderr)
