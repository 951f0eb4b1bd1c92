"""What a study declares (design notes, "Study seam"): a typed config whose defaults are the
thesis's values, a typed per-seed result, and a function from (config, seed) to that result;
beside them the metrics, claims, figures and notes that its page shows.

A study never loops over seeds, computes statistics or writes files: the framework runs its
seeds (locally or on Ray), caches each finished (config, seed), computes every mean's CI and
every claim's paired test, and writes the JSON, the page and the plots. ``docs/research.md``
shows how to add a study or a parameter.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Annotated, Generic, Literal, Protocol, TypeVar

from pydantic import BaseModel, ConfigDict, Field

from robot.reproduce.framework.plots import Figure

NAME_PATTERN = re.compile(r"[A-Za-z][A-Za-z0-9]*(-[A-Za-z0-9]+)*")
RESERVED_NAMES = frozenset({"merge"})
"""Words ``goalagent reproduce`` reads as a sub-command, never as a study."""


@dataclass(frozen=True)
class Reading:
    """What the thesis says about an open choice that a config field decides, with where
    (section, equation, table): ``learn_in_exploit: Annotated[bool, Reading("App. A: ...")]``.
    The page's "Deviations and open choices" lists every such field beside its value as run
    and the field's docstring (what the code does), so the list cannot drift from the code."""

    thesis: str


@dataclass(frozen=True)
class Deviation:
    """A fixed difference from the thesis that no parameter decides (a simulated can, a lift
    beside the table): what the thesis has, with where, and what the code does instead."""

    topic: str
    thesis: str
    code: str


class StudyConfig(BaseModel):
    """A study's parameters. Subclass it with one field per parameter: the thesis's (or the
    source's) value as the default, and a docstring under the field saying what it is and
    where the thesis gives it (equation, section, table). ``--set KEY=VALUE`` and ``--grid``
    set fields by name, validated against their types."""

    model_config = ConfigDict(frozen=True, extra="forbid", use_attribute_docstrings=True,
                              validate_default=True)

    @classmethod
    def reading(cls, name: str) -> Reading | None:
        """The thesis's reading of field ``name`` if it is an open choice (see ``Reading``);
        a subclass that only changes a default keeps the class's that declared it."""
        for klass in cls.__mro__:
            info = getattr(klass, "model_fields", {}).get(name)
            if info is None:
                continue
            found = next((m for m in info.metadata if isinstance(m, Reading)), None)
            if found is not None:
                return found
        return None

    @classmethod
    def describe(cls, name: str) -> str:
        """The docstring of field ``name``: a subclass that only changes a default keeps the
        text of the class that documented the field."""
        for klass in cls.__mro__:
            info = getattr(klass, "model_fields", {}).get(name)
            if info is not None and info.description:
                return " ".join(info.description.split())
        return ""


class ScaledConfig(StudyConfig):
    """The config of a study whose runs shrink: trials, problems and budgets scale with
    ``scale`` (``--quick`` and the tests run small)."""

    scale: Annotated[float, Field(gt=0.0, le=1.0)] = 1.0
    """Run size in (0, 1]: 1 is the full size of the thesis's or the paper's runs."""


class SeedResult(BaseModel):
    """One seed's measurements (subclass it): numbers, strings, lists and nested results,
    None for a value the seed did not reach. Plain JSON only: no NaN, no infinity."""

    model_config = ConfigDict(frozen=True, extra="forbid", allow_inf_nan=False)


C = TypeVar("C", bound=StudyConfig)
R = TypeVar("R", bound=SeedResult)


class Progress(Protocol):
    """Called by a seed's run with the fraction of that seed done (0..1), now and then."""

    def __call__(self, fraction: float) -> None: ...


T = TypeVar("T")


def in_turn(items: Iterable[T], progress: Progress) -> Iterator[T]:
    """Each item in turn; after each, ``progress`` hears the fraction of the items done (the
    loop of a seed's run over its modes, methods or configurations)."""
    listed = list(items)
    for index, item in enumerate(listed):
        yield item
        progress((index + 1) / len(listed))


@dataclass(frozen=True)
class Metric(Generic[R]):
    """One row of the page's table: a number measured in each seed. The framework reports its
    mean, sample sd and 95% bootstrap CI over the seeds that have it."""

    key: str
    """Its name in the JSON summary and in ``sweep`` plots, e.g. ``mux6.final_accuracy``."""
    label: str
    """The row's text on the page."""
    value: Callable[[R], float | None]
    """The seed's value; None where the seed did not reach it (not averaged)."""
    reference: float | None = None
    """The thesis's or the literature's value, if there is one."""
    source: str = ""
    """Where the reference comes from, e.g. "Wilson 1995, Fig. 3"."""


Direction = Literal["greater", "less", "same"]


@dataclass(frozen=True)
class Claim:
    """A claim the study tests over its seeds: ``metric`` is greater than, less than or the
    same as ``versus``, another metric (paired by seed) or a number (each seed against it)."""

    text: str
    """The claim in words, with where it is made (section, figure)."""
    metric: str
    versus: str | float
    direction: Direction = "greater"


def no_claims(config: StudyConfig) -> Sequence[Claim]:
    """For a study that compares nothing."""
    return ()


def no_listings(config: StudyConfig, seeds: Sequence[SeedResult]) -> str:
    """For a study whose page needs no tables beyond its metrics."""
    return ""


@dataclass(frozen=True)
class Study(Generic[C, R]):
    """A named study (see the module doc). Every callable must be a module-level function, so
    that seeds can run in other processes."""

    name: str
    description: str
    config: type[C]
    result: type[R]
    run: Callable[[C, int, Progress], R]
    """(config, seed, progress) -> that seed's result; seed every random generator from
    ``seed``."""
    metrics: Callable[[C], Sequence[Metric[R]]]
    figures: Callable[[C, Sequence[R]], Sequence[Figure]]
    notes: str = ""
    """Markdown under the table: the setup, what differs from the thesis and why."""
    claims: Callable[[C], Sequence[Claim]] = no_claims
    listings: Callable[[C, Sequence[R]], str] = no_listings
    """Markdown after the notes: tables the thesis prints that are not one number beside
    another (learned rules, every part model)."""
    quick: Mapping[str, object] = field(default_factory=dict)
    """The config values of ``--quick`` (and of the test suite's small runs)."""
    default_seeds: int = 10
    headline: tuple[str, ...] = ()
    """Metric keys that ``goalagent sweep`` plots against the swept parameter."""
    deviations: tuple[Deviation, ...] = ()
    """Fixed differences from the thesis (or the study's source) that no parameter decides;
    the page lists them after the config's open choices."""

    def __post_init__(self) -> None:
        if not NAME_PATTERN.fullmatch(self.name) or self.name in RESERVED_NAMES:
            raise ValueError(f"study name {self.name!r} must be words joined by '-', not "
                             f"{' or '.join(sorted(RESERVED_NAMES))}")
        if "\n" in self.description or not self.description:
            raise ValueError(f"study {self.name}: the description must be one line")
        unknown = set(self.quick) - set(self.config.model_fields)
        if unknown:
            raise ValueError(f"study {self.name}: quick sets unknown parameters {unknown}")

    def default_config(self) -> C:
        """The thesis's values."""
        return self.config()

    def quick_config(self) -> C:
        """The values of ``--quick``."""
        return self.config.model_validate(dict(self.quick))
