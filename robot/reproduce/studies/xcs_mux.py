"""``xcs-mux``: XCS on the 6- and 11-multiplexer as Wilson (1995) ran it.

Wilson reports 100% performance on the 6-multiplexer after about 5,000 problems with N = 400,
and on the 11-multiplexer after about 15,000 with N = 800.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Annotated

from pydantic import Field

from robot.reproduce.framework import (
    Claim,
    Deviation,
    Figure,
    Metric,
    Progress,
    Reference,
    SeedResult,
    Study,
)
from robot.reproduce.studies.common.lcs import (
    MuxRun,
    curve_panels,
    explore_problems,
    multiplexer_experiment,
)
from robot.reproduce.studies.common.xcs import Probability, XcsParameters, xcs_keywords

PROBLEMS = {"mux6": 2, "mux11": 3}
"""Per problem: its address bits."""
WILSON_N = {"mux6": 400, "mux11": 800}
WILSON_PROBLEMS_TO_100 = {"mux6": 5_000, "mux11": 15_000}
LABELS = {"mux6": "6-multiplexer", "mux11": "11-multiplexer"}


class Config(XcsParameters):
    """Wilson's multiplexer settings (1995), with Butz & Wilson's power-law accuracy (ν = 5)
    and GA subsumption."""

    N: Annotated[int, Field(ge=2)] | None = None  # type: ignore[assignment]
    """Population size on both multiplexers; None: Wilson's, 400 on the 6- and 800 on the
    11-multiplexer."""
    gamma: Probability = 0.0
    """γ plays no part in single-step problems."""
    problems_mux6: Annotated[int, Field(ge=1)] = 10_000
    """Explore problems on the 6-multiplexer in a full run (scaled, at least 100)."""
    problems_mux11: Annotated[int, Field(ge=1)] = 30_000
    """Explore problems on the 11-multiplexer in a full run (scaled, at least 100)."""

    def population(self, problem: str) -> int:
        return self.N if self.N is not None else WILSON_N[problem]

    def problems(self, problem: str) -> int:
        full = self.problems_mux6 if problem == "mux6" else self.problems_mux11
        return explore_problems(full, self.scale)


class Result(SeedResult):
    mux6: MuxRun
    mux11: MuxRun


def run(config: Config, seed: int, progress: Progress) -> Result:
    """Both multiplexers, one after the other."""
    sizes = {name: config.problems(name) for name in PROBLEMS}
    total, done, runs = sum(sizes.values()), 0, {}
    for name, address_bits in PROBLEMS.items():
        runs[name] = multiplexer_experiment(
            address_bits, sizes[name], xcs_keywords(config, N=config.population(name)), seed,
            lambda fraction, done=done, size=sizes[name]: progress(
                (done + fraction * size) / total))
        done += sizes[name]
    return Result(**runs)


def metrics(config: Config) -> list[Metric[Result]]:
    rows: list[Metric[Result]] = []
    for name in PROBLEMS:
        label = LABELS[name]

        def part(seed: Result, name: str = name) -> MuxRun:
            return getattr(seed, name)

        rows += [
            Metric(f"{name}.final_accuracy",
                   f"{label}: fraction correct, last 50 exploit problems",
                   lambda s, part=part: part(s).final_accuracy, 1.0, "Wilson 1995: 100%"),
            Metric(f"{name}.problems_to_99",
                   f"{label}: explore problems until 50/50 correct for good",
                   lambda s, part=part: part(s).problems_to_99, WILSON_PROBLEMS_TO_100[name],
                   f"Wilson 1995: about {WILSON_PROBLEMS_TO_100[name]:,}, "
                   f"N = {WILSON_N[name]}"),
            Metric(f"{name}.first_at_99", f"{label}: explore problems until 50/50 correct "
                   "the first time", lambda s, part=part: part(s).first_at_99),
            Metric(f"{name}.macro_classifiers", f"{label}: macro-classifiers at the end",
                   lambda s, part=part: part(s).final_macro_classifiers),
        ]
    return rows


def claims(config: Config) -> list[Claim]:
    return [Claim(f"XCS solves the {LABELS[name]} (all of the last 50 exploit problems right "
                  f"for good) within about {WILSON_PROBLEMS_TO_100[name]:,} explore problems "
                  "(Wilson 1995)", f"{name}.problems_to_99", WILSON_PROBLEMS_TO_100[name],
                  "less") for name in PROBLEMS]


def figures(config: Config, seeds: Sequence[Result]) -> list[Figure]:
    """Both multiplexers on one figure: fraction correct, and population size."""
    runs = {f"{LABELS[name]}, N = {config.population(name)}": [getattr(s, name) for s in seeds]
            for name in PROBLEMS}
    references = [Reference(1.0, "100% (Wilson 1995)")] + [
        Reference(WILSON_PROBLEMS_TO_100[name], f"Wilson 1995: {LABELS[name]} at 100% by "
                  f"about {WILSON_PROBLEMS_TO_100[name]:,}", vertical=True) for name in PROBLEMS]
    return [Figure("curves", "XCS on the 6- and 11-multiplexer", curve_panels(
        runs, "fraction correct (last 50 exploit problems)", references, (0.4, 1.02)))]


STUDY = Study(
    name="xcs-mux",
    description="XCS on the 6- and 11-multiplexer (Wilson 1995): fraction correct and "
                "population size against explore problems",
    config=Config, result=Result, run=run, metrics=metrics, claims=claims, figures=figures,
    quick={"scale": 0.05},
    headline=("mux6.final_accuracy", "mux6.problems_to_99", "mux11.final_accuracy",
              "mux11.problems_to_99"),
    deviations=(
        Deviation("Algorithm", "Wilson (1995) describes the first XCS.", "Butz & Wilson's "
                  "(2001) algorithmic description of it, with the thesis's separate learning "
                  "rates (App. A, eqs 7.1-7.7), all set to Wilson's β here."),
    ),
    notes="""\
**Setup** (Wilson 1995, with Butz & Wilson's 2001 algorithm): explore and exploit problems
alternate; each problem is a uniformly random input; reward 1000 for the right output, 0
otherwise; an exploit problem acts greedily and learns nothing. Performance is the fraction of
the last 50 exploit problems answered correctly, plotted against explore problems. The
parameters as run are listed below (Wilson's: N = 400 on the 6- and 800 on the
11-multiplexer, β = 0.2, α = 0.1, ε0 = 10, ν = 5, θGA = 25, χ = 0.8, μ = 0.04, θdel = 20,
δ = 0.1, θsub = 20, P# = 0.33, p_I = 10, ε_I = 0, F_I = 0.01, GA subsumption on, action-set
subsumption off). "Until 50/50 correct for good" is the explore problem from which the
fraction over the last 50 exploit problems stayed at 0.99 or more (all 50 right) to the end
of the run; "the first time" is when it first got there.""",
)
