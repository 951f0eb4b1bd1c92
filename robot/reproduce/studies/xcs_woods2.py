"""``xcs-woods2``: XCS as Wilson's animat in Woods2 (Wilson 1995).

The optimum is 1.7 steps to food on average (1.6875 exactly over the map's 288 blank cells);
Wilson's XCS comes down to about 2 steps within 4,000 problems.
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
    Study,
)
from robot.reproduce.studies.common.lcs import (
    WoodsRun,
    explore_problems,
    map_optimum,
    woods_experiment,
    woods_figure,
    woods_metrics,
)
from robot.reproduce.studies.common.lcs_problems import WOODS2, WOODS2_CODES
from robot.reproduce.studies.common.xcs import Probability, XcsParameters, xcs_keywords

WILSON_STEPS = 2.0
"""Wilson 1995: about 2 steps to food within 4,000 problems."""


class WoodsConfig(XcsParameters):
    """Wilson's Woods2 settings (1995), with Butz & Wilson's power-law accuracy (ν = 5) and GA
    subsumption."""

    N: Annotated[int, Field(ge=8)] = 800
    mu: Probability = 0.01
    p_hash: Probability = 0.5
    problems: Annotated[int, Field(ge=1)] = 4_000
    """Explore problems in a full run (scaled, at least 100)."""
    step_limit: Annotated[int, Field(ge=1)] = 50
    """A problem not at food after this many steps ends (as in xcslib and XCSJava)."""


def run(config: WoodsConfig, seed: int, progress: Progress) -> WoodsRun:
    return woods_experiment(WOODS2, WOODS2_CODES, explore_problems(config.problems, config.scale),
                            xcs_keywords(config), seed, progress, config.step_limit)


def metrics(config: WoodsConfig) -> list[Metric[WoodsRun]]:
    return woods_metrics("woods2", "Woods2", lambda seed: seed,
                         map_optimum(WOODS2, tuple(WOODS2_CODES.items())),
                         (WILSON_STEPS, "Wilson 1995: about 2 within 4,000 problems"),
                         WILSON_STEPS)


def claims(config: WoodsConfig) -> list[Claim]:
    return [Claim("XCS comes down to 2 steps to food or fewer within 4,000 explore problems "
                  "(Wilson 1995: about 2)", "woods2.final_steps", WILSON_STEPS, "less")]


def figures(config: WoodsConfig, seeds: Sequence[WoodsRun]) -> list[Figure]:
    return [woods_figure({"goalagent XCS": list(seeds)}, "steps",
                         f"XCS in Woods2 (N = {config.N})",
                         [Reference(WILSON_STEPS, "Wilson 1995: about 2 within 4,000")],
                         (0.0, 8.0))]


STUDY = Study(
    name="xcs-woods2",
    description="XCS as Wilson's animat in Woods2 (Wilson 1995): steps to food against "
                "explore problems",
    config=WoodsConfig, result=WoodsRun, run=run, metrics=metrics, claims=claims,
    figures=figures, quick={"scale": 0.05},
    headline=("woods2.final_steps", "woods2.problems_to_near", "woods2.macro_classifiers"),
    deviations=(
        Deviation("Accuracy", "Wilson (1995): κ = exp(ln α (ε − ε0)/ε0).", "the power law "
                  "κ = α (ε/ε0)^−ν of Butz & Wilson (2001) and the thesis (eq. 7.6)."),
        Deviation("Map", "Wilson's Woods2.", "the 30 × 15 map distributed with Lanzi's "
                  "xcslib."),
    ),
    notes="""\
**Setup** (Wilson 1995): Woods2 is the 30 × 15 toroidal map distributed with Lanzi's xcslib,
rocks O and Q, food F and G; the animat senses its 8 neighbours clockwise from north, 3 bits
each (blank 000, O 010, Q 011, F 110, G 111: 24 bits), and moves into one of them (a rock
blocks the move). A problem starts on a random blank cell and ends on food (reward 1000) or
after `step_limit` steps. Explore and exploit problems alternate; the curve is the mean steps
to food over the last 50 exploit problems (cut off at 8 steps: the first problems' long walks
go beyond). Wilson's parameters are the defaults below (N = 800, γ = 0.71, μ = 0.01,
P# = 0.5, ...). Wilson's 1995 accuracy was exponential (κ = exp(ln α (ε − ε0)/ε0)); this is
the power law of Butz & Wilson and the thesis (eq. 7.6).""",
)
