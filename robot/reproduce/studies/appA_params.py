"""``appA-params``: the thesis's XCS settings (Table 7.1) on Woods2 and on the 6-multiplexer.

Table 7.1 was chosen for NAO experiments of a few dozen trials ("the population size limit and
GA threshold are both decreased due to much less experiment trials compared with the thousands
of trials in woods2"). This runs it on the classic problems as a regression test of those
settings — it must run without errors — and, beside it, the same settings with the
population size the problems are known to need (N = 800 in Woods2, 400 on the 6-multiplexer),
which shows what N = 100 costs there.
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
    WoodsRun,
    curve_panels,
    explore_problems,
    map_optimum,
    multiplexer_experiment,
    woods_experiment,
    woods_figure,
    woods_metrics,
)
from robot.reproduce.studies.common.lcs_problems import WOODS2, WOODS2_CODES
from robot.reproduce.studies.common.xcs import Table71, xcs_keywords

RUNS = ("woods2", "woods2_larger_n", "mux6", "mux6_larger_n")
WORK = {"woods2": 0.4, "woods2_larger_n": 0.4, "mux6": 0.1, "mux6_larger_n": 0.1}
"""Rough share of a seed's time each run takes (for the progress bar)."""


class Config(Table71):
    """Table 7.1 (θsub = 20, δ = 0.1 and GA subsumption, which it does not give, are the
    learner's own), and the population sizes Wilson used beside it."""

    larger_n_woods2: Annotated[int, Field(ge=8)] = 800
    """N of the Woods2 run beside Table 7.1's (Wilson 1995)."""
    larger_n_mux6: Annotated[int, Field(ge=2)] = 400
    """N of the 6-multiplexer run beside Table 7.1's (Wilson 1995)."""
    step_limit: Annotated[int, Field(ge=1)] = 20
    """Table 7.1's N_s: steps of a Woods2 problem at most."""
    problems_woods2: Annotated[int, Field(ge=1)] = 4_000
    """Explore problems in Woods2 in a full run (scaled, at least 100)."""
    problems_mux6: Annotated[int, Field(ge=1)] = 10_000
    """Explore problems on the 6-multiplexer in a full run (scaled, at least 100)."""

    def population(self, run: str) -> int:
        return {"woods2": self.N, "mux6": self.N, "woods2_larger_n": self.larger_n_woods2,
                "mux6_larger_n": self.larger_n_mux6}[run]


class Result(SeedResult):
    woods2: WoodsRun
    woods2_larger_n: WoodsRun
    mux6: MuxRun
    mux6_larger_n: MuxRun


def run(config: Config, seed: int, progress: Progress) -> Result:
    runs: dict[str, WoodsRun | MuxRun] = {}
    done = 0.0
    for name in RUNS:
        params = xcs_keywords(config, N=config.population(name))

        def report(fraction: float, done: float = done, share: float = WORK[name]) -> None:
            progress(done + share * fraction)

        if name.startswith("woods2"):
            runs[name] = woods_experiment(
                WOODS2, WOODS2_CODES, explore_problems(config.problems_woods2, config.scale),
                params, seed, report, config.step_limit)
        else:
            runs[name] = multiplexer_experiment(
                2, explore_problems(config.problems_mux6, config.scale), params, seed, report)
        done += WORK[name]
    return Result(**runs)


def metrics(config: Config) -> list[Metric[Result]]:
    optimum = map_optimum(WOODS2, tuple(WOODS2_CODES.items()))
    rows: list[Metric[Result]] = []
    for name in ("woods2", "woods2_larger_n"):
        rows += woods_metrics(name, f"Woods2, Table 7.1 with N = {config.population(name)}",
                              lambda seed, name=name: getattr(seed, name), optimum, None,
                              2.0)
    for name in ("mux6", "mux6_larger_n"):
        label = f"6-multiplexer, Table 7.1 with N = {config.population(name)}"
        rows += [
            Metric(f"{name}.final_accuracy", f"{label}: fraction correct, last 50 exploit "
                   "problems", lambda s, name=name: getattr(s, name).final_accuracy, 1.0,
                   "a perfect score (no thesis value)"),
            Metric(f"{name}.problems_to_99", f"{label}: explore problems until 50/50 correct "
                   "for good", lambda s, name=name: getattr(s, name).problems_to_99),
        ]
    return rows


def claims(config: Config) -> list[Claim]:
    return [
        Claim(f"Table 7.1's N = {config.N} is too small for Woods2: with "
              f"N = {config.larger_n_woods2} and nothing else changed, XCS ends nearer to food",
              "woods2.final_steps", "woods2_larger_n.final_steps", "greater"),
        Claim(f"Table 7.1's N = {config.N} is too small for the 6-multiplexer: with "
              f"N = {config.larger_n_mux6} and nothing else changed, XCS ends more accurate",
              "mux6_larger_n.final_accuracy", "mux6.final_accuracy", "greater"),
    ]


def figures(config: Config, seeds: Sequence[Result]) -> list[Figure]:
    def runs(names: tuple[str, str]) -> dict:
        return {f"Table 7.1 (N = {config.population(names[0])})"
                if index == 0 else f"Table 7.1 with N = {config.population(name)}":
                [getattr(seed, name) for seed in seeds] for index, name in enumerate(names)}

    return [
        woods_figure(runs(("woods2", "woods2_larger_n")), "woods2",
                     f"Table 7.1's XCS in Woods2 (θGA = {config.theta_ga}, P# = "
                     f"{config.p_hash:g}, N_s = {config.step_limit})", [],
                     (0.0, config.step_limit + 1)),
        Figure("mux6", f"Table 7.1's XCS on the 6-multiplexer (θGA = {config.theta_ga}, P# = "
               f"{config.p_hash:g})", curve_panels(
                   runs(("mux6", "mux6_larger_n")),
                   "fraction correct (last 50 exploit problems)", [Reference(1.0, "100%")],
                   (0.4, 1.02))),
    ]


STUDY = Study(
    name="appA-params",
    description="The thesis's XCS settings (Table 7.1) on Woods2 and the 6-multiplexer, as a "
                "regression test of those settings",
    config=Config, result=Result, run=run, metrics=metrics, claims=claims, figures=figures,
    quick={"scale": 0.05},
    headline=("woods2.final_steps", "woods2_larger_n.final_steps", "mux6.final_accuracy",
              "mux6_larger_n.final_accuracy"),
    deviations=(
        Deviation("Problems", "Table 7.1's settings were chosen for the NAO's search task; "
                  "the thesis runs them on no classic problem.", "Woods2 and the "
                  "6-multiplexer as a regression test; θsub = 20, δ = 0.1 and GA subsumption "
                  "(not in Table 7.1) are Wilson's."),
    ),
    notes="""\
**Setup**: Table 7.1 — N = 100, γ = 0.7, β_p = β_ε = β_F = 0.2, χ = 0.8, μ = 0.04, ε0 = 10,
α = 0.1, ν = 5, p⁰ = 10, ε⁰ = 0, F⁰ = 0.01, P# = 0.6, θGA = 5, θdel = 20 — with the trial step
limit N_s on Woods2 (the same map, sensing and protocol as `xcs-woods2`) and on the
6-multiplexer (as `xcs-mux`, reward 1000/0). Not given by the table: θsub = 20, δ = 0.1, GA
subsumption on. The thesis reports no numbers for these problems; the references are the
problems' best possible values. The "with N = 800 / 400" runs change only N, to the
population sizes Wilson used: the difference between the two is what N = 100 costs.""",
)
