"""What a reproduction declares, and how `goalagent reproduce` finds it by name.

A reproduction is a module ``robot/reproduce/<name with - as _>.py`` that defines
``REPRODUCTION = Reproduction(...)``: its name, a one-line description, a function that runs
one seed, and three pure functions over the seeds' results — the summary, the comparison
against the thesis or the literature, and the figures. The runner (`robot.reproduce.runner`)
does everything else: seeds in parallel processes, progress, the JSON, the markdown table with
the gaps, the PNG plots. See ``robot/reproduce/__init__.py`` for a worked outline.
"""

from __future__ import annotations

import importlib
import math
import pkgutil
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Protocol

SeedResult = dict
"""One seed's measurements: JSON-able numbers, strings, lists and dicts (curves as lists)."""

NAME_PATTERN = re.compile(r"[A-Za-z][A-Za-z0-9]*(-[A-Za-z0-9]+)*")


class Progress(Protocol):
    """Called by a seed's run with the fraction of that seed done (0..1), now and then."""

    def __call__(self, fraction: float) -> None: ...


@dataclass(frozen=True)
class Comparison:
    """One row of the reproduction's table: a measured quantity beside its reference."""

    quantity: str
    measured: float | None
    spread: float | None = None
    """Standard deviation over seeds (None: a single number)."""
    reference: float | None = None
    """The thesis's or literature's value (None: there is none to compare with)."""
    source: str = ""
    """Where the reference comes from, e.g. "Wilson 1995, Fig. 3"."""

    @property
    def gap(self) -> float | None:
        """measured - reference, when both exist."""
        if self.measured is None or self.reference is None or math.isnan(self.measured):
            return None
        return self.measured - self.reference


@dataclass(frozen=True)
class Series:
    """One curve: the same x for every seed, one y list per seed (mean ± std is plotted)."""

    label: str
    x: Sequence[float]
    runs: Sequence[Sequence[float]]


@dataclass(frozen=True)
class Reference:
    """A reference value drawn as a dashed line (horizontal, or vertical with ``vertical``)."""

    value: float
    label: str
    vertical: bool = False


@dataclass(frozen=True)
class Panel:
    """One set of axes."""

    xlabel: str
    ylabel: str
    series: Sequence[Series]
    references: Sequence[Reference] = ()
    ylim: tuple[float, float] | None = None


@dataclass(frozen=True)
class Figure:
    """One PNG, ``<out>/<reproduction>-<stem>.png``, with panels side by side."""

    stem: str
    title: str
    panels: Sequence[Panel]


@dataclass(frozen=True)
class Reproduction:
    """A named reproduction (see the module doc); every callable must be a module-level
    function so that seeds can run in other processes."""

    name: str
    description: str
    run_seed: Callable[[int, float, Progress], SeedResult]
    """(seed, scale, progress) -> that seed's measurements; scale in (0, 1] shrinks the run
    (1 is the full size the reproduction's source used)."""
    summarize: Callable[[list[SeedResult]], dict]
    """All seeds' results -> the ``summary`` object of NAME.json."""
    compare: Callable[[dict, list[SeedResult]], list[Comparison]]
    """(summary, seeds) -> the rows of NAME.md's table."""
    figures: Callable[[list[SeedResult]], list[Figure]]
    """Seeds -> the plots."""
    notes: str = ""
    """Markdown shown under the table: the setup, the parameters, what differs and why."""
    listings: Callable[[dict, list[SeedResult]], str] | None = None
    """(summary, seeds) -> more Markdown under the notes: tables the thesis prints that are
    not one number beside another (learned rules, every part model), or None."""
    quick_scale: float = 0.05
    """The scale of ``--quick`` (and of the test suite's small runs)."""
    default_seeds: int = 10

    def __post_init__(self) -> None:
        if not NAME_PATTERN.fullmatch(self.name):
            raise ValueError(f"reproduction name {self.name!r} must be words joined by '-'")
        if "\n" in self.description or not self.description:
            raise ValueError(f"reproduction {self.name}: the description must be one line")


class UnknownReproduction(LookupError):
    """No reproduction has that name."""


def module_name(name: str) -> str:
    """The module that holds reproduction ``name``: ``xcs-mux`` -> ``robot.reproduce.xcs_mux``."""
    return f"{__package__}.{name.replace('-', '_')}"


def find(name: str) -> Reproduction:
    """The reproduction called ``name``, or UnknownReproduction listing the known names."""
    if not NAME_PATTERN.fullmatch(name):
        raise UnknownReproduction(_unknown(name))
    try:
        module = importlib.import_module(module_name(name))
    except ModuleNotFoundError as error:
        if error.name != module_name(name):
            raise
        raise UnknownReproduction(_unknown(name)) from None
    reproduction = getattr(module, "REPRODUCTION", None)
    if not isinstance(reproduction, Reproduction) or reproduction.name != name:
        raise UnknownReproduction(_unknown(name))
    return reproduction


def registered() -> list[Reproduction]:
    """Every reproduction in this package, by name."""
    found = []
    package = importlib.import_module(__package__)
    for info in pkgutil.iter_modules(package.__path__):
        if info.name.startswith("_"):
            continue
        module = importlib.import_module(f"{__package__}.{info.name}")
        reproduction = getattr(module, "REPRODUCTION", None)
        if isinstance(reproduction, Reproduction):
            found.append(reproduction)
    return sorted(found, key=lambda reproduction: reproduction.name)


def _unknown(name: str) -> str:
    names = ", ".join(reproduction.name for reproduction in registered())
    return f"no reproduction called {name!r} (known: {names or 'none'})"


def mean_and_std(values: Sequence[float | None]) -> tuple[float | None, float | None]:
    """Mean and population standard deviation of the values that exist (None if none do)."""
    present = [float(value) for value in values if value is not None and not math.isnan(value)]
    if not present:
        return None, None
    mean = sum(present) / len(present)
    return mean, math.sqrt(sum((value - mean) ** 2 for value in present) / len(present))


def markdown_table(headers: Sequence[str], rows: Sequence[Sequence[object]]) -> str:
    """A Markdown table; cells as ``str`` gives them, a ``|`` inside a cell escaped."""
    def line(cells: Sequence[object]) -> str:
        return "| " + " | ".join(str(cell).replace("|", "\\|") for cell in cells) + " |"
    return "\n".join([line(headers), "|" + "---|" * len(headers)] + [line(r) for r in rows])
