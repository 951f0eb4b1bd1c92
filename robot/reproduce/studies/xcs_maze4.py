"""``xcs-maze4``: XCS in Lanzi's Maze4, with and without generalisation (Lanzi 1997, 1999).

A classic problem the learner was not built on. Maze4 allows few generalisations; Lanzi
reported that there XCS's generalisation can keep it from the optimal policy (overgeneral
classifiers), while XCS without don't-care symbols reaches the optimum easily. The runs
compare exactly that: Wilson's woods settings with P# = 0.5 and with P# = 0.33, and the same
XCS with no # at all (P# = 0, μ = 0: covering makes only fully specific classifiers and nothing
generalises them). The last is the check on the multi-step machinery (eq. 7.2, the last step
of a trial, the step limit): it must find the optimum of 3.5 steps.
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
    SeedResult,
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
from robot.reproduce.studies.common.lcs_problems import MAZE4, MAZE_CODES
from robot.reproduce.studies.common.xcs import Probability, xcs_keywords
from robot.reproduce.studies.xcs_woods2 import WoodsConfig

RUNS = ("generalising", "generalising_p033", "specific")


class Config(WoodsConfig):
    """Wilson's woods settings with Lanzi's population size for his mazes (N = 1600)."""

    N: Annotated[int, Field(ge=8)] = 1600
    p_hash_low: Probability = 0.33
    """P# of the second generalising XCS (the first has ``p_hash``)."""
    near_optimal: Annotated[float, Field(gt=0.0)] = 4.0
    """Within half a step of the optimum (3.5): "near the optimum" in the table."""

    def keywords(self, run: str) -> dict[str, object]:
        """The XCS of each run: P# = p_hash, P# = p_hash_low, or no # at all."""
        changes = {"generalising": {}, "generalising_p033": {"p_hash": self.p_hash_low},
                   "specific": {"p_hash": 0.0, "mu": 0.0}}[run]
        return xcs_keywords(self, **changes)

    def label(self, run: str) -> str:
        return {"generalising": f"XCS, P# = {self.p_hash:g}",
                "generalising_p033": f"XCS, P# = {self.p_hash_low:g}",
                "specific": "XCS without # (P# = 0, μ = 0)"}[run]


class Result(SeedResult):
    generalising: WoodsRun
    generalising_p033: WoodsRun
    specific: WoodsRun


def run(config: Config, seed: int, progress: Progress) -> Result:
    problems = explore_problems(config.problems, config.scale)
    runs = {}
    for index, name in enumerate(RUNS):
        runs[name] = woods_experiment(
            MAZE4, MAZE_CODES, problems, config.keywords(name), seed,
            lambda fraction, index=index: progress((index + fraction) / len(RUNS)),
            config.step_limit)
    return Result(**runs)


def metrics(config: Config) -> list[Metric[Result]]:
    optimum = map_optimum(MAZE4, tuple(MAZE_CODES.items()))
    rows: list[Metric[Result]] = []
    for name in RUNS:
        rows += woods_metrics(name, config.label(name),
                              lambda seed, name=name: getattr(seed, name), optimum, None,
                              config.near_optimal)
    return rows


def claims(config: Config) -> list[Claim]:
    return [
        Claim("XCS without don't-cares reaches the optimum in Maze4 (Lanzi 1997): it ends "
              f"at {config.near_optimal:g} steps or fewer", "specific.final_steps",
              config.near_optimal, "less"),
        Claim("In Maze4 generalisation keeps XCS from the optimal policy (Lanzi 1997, 1999): "
              f"with P# = {config.p_hash:g} it ends with more steps to food than without #",
              "generalising.final_steps", "specific.final_steps", "greater"),
    ]


def figures(config: Config, seeds: Sequence[Result]) -> list[Figure]:
    runs = {config.label(name): [getattr(seed, name) for seed in seeds] for name in RUNS}
    return [woods_figure(runs, "steps", f"XCS in Maze4 (N = {config.N})", [],
                         (0.0, config.step_limit + 1))]


STUDY = Study(
    name="xcs-maze4",
    description="XCS in Lanzi's Maze4 with and without generalisation (Lanzi 1997, 1999): "
                "steps to food against explore problems",
    config=Config, result=Result, run=run, metrics=metrics, claims=claims, figures=figures,
    quick={"scale": 0.025},
    headline=("generalising.final_steps", "generalising_p033.final_steps",
              "specific.final_steps"),
    deviations=(
        Deviation("Specify", "Lanzi's XCS adds the Specify operator in such mazes.",
                  "not implemented: this is the thesis's XCS (App. A)."),
    ),
    notes="""\
**Setup**: Maze4 as in Lanzi (1997) and xcsf's `maze4.txt`: 8 × 8, walls all round, one food
cell; the animat senses its 8 neighbours clockwise from north, 2 bits each (blank 00,
obstacle 10, food 11: 16 bits), moves into one of them (an obstacle blocks the move). The
optimum is 3.5 steps (BFS over the 26 blank cells). Protocol and parameters as `xcs-woods2`
(explore and exploit problems alternate, a step limit, reward 1000 at food) with N = 1600;
exploit problems learn nothing (thesis App. A: learning only in explore mode).

**What the literature says**: Lanzi (1997, "A study of the generalization capabilities of
XCS"; 1999, "An analysis of generalization in the XCS classifier system") found that in mazes
where few generalisations are possible (Maze4, Maze5, Maze6) XCS's generalisation can keep it
from the optimal policy — overgeneral classifiers that are rarely contradicted — and that
often it does not reach a stable solution; XCS without don't-care symbols reaches the optimum
easily; his Specify operator (not part of this XCS) repairs the generalising one. No
per-problem number is quoted here from those papers: the reference is the optimum.""",
)
