"""``ch5-transfer``: thesis Table 5.4, learning the cans with and without transfer.

Per seed, in truth and in camera perception: the cans o1..o5 presented in the thesis's order
(then the two new mechanisms, ``slide`` and ``pedal``), each learned with Algorithm 6 from the
cans before it and, for N without transfer, with Algorithm 4 (``studies/common/ch5.py``).
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import product
from typing import Annotated

from robot.reproduce.framework import (
    Claim,
    Figure,
    Metric,
    Panel,
    Progress,
    Reading,
    Reference,
    SeedResult,
    Series,
    Study,
    in_turn,
    markdown_table,
)
from robot.reproduce.studies.common.ch5 import (
    CH5_DEVIATIONS,
    NEW_CANS,
    THESIS_CANS,
    PartLearningConfig,
    TransferRow,
    found_pair,
    most_frequent,
    transfer_run,
    true_pair,
)

THESIS = {"o1": (36, None, None), "o2": (65, 29, "o1"), "o3": (53, 1, "o1"),
          "o4": (83, 3, "o2"), "o5": (80, 11, "o2")}
"""Table 5.4 as printed: (N without, N with transfer, source)."""


class Config(PartLearningConfig):
    """The thesis's cans in its order, then the two new mechanisms."""

    cans: tuple[str, ...] = THESIS_CANS + NEW_CANS
    stop_at_goal: Annotated[bool, Reading(
        "§5.5.1: \"The purpose is not to learn every prediction model ... but is to achieve "
        "the goal condition (5.9) as fast as possible\"; §5.5.2: \"Action selection "
        "continues until the task goal is achieved\"; yet Algorithm 6's line 31 hands the "
        "novel parts to Algorithm 4, which explores every pair before it selects.")] = True
    """Whether transfer's last resort (Algorithm 6, line 31: Algorithm 4 on the novel-looking
    parts) stops at the first action that reaches the goal (true), or explores every pair
    first as Algorithm 4 does (false)."""


class Result(SeedResult):
    perceptions: dict[str, dict[str, TransferRow]]
    """perception -> can -> its run with and without transfer."""


def run(config: Config, seed: int, progress: Progress) -> Result:
    """Every can in every perception, each from an empty database."""
    return Result(perceptions={perception: transfer_run(seed, config, perception,
                                                        config.stop_at_goal)
                               for perception in in_turn(config.perceptions, progress)})


def metrics(config: Config) -> list[Metric[Result]]:
    rows: list[Metric[Result]] = []
    for perception, can in product(config.perceptions, config.cans):
        def get(seed: Result, p: str = perception, c: str = can) -> TransferRow:
            return seed.perceptions[p][c]

        key, where = f"{perception}.{can}", f"{can} ({perception})"
        without, with_, _ = THESIS.get(can, (None, None, None))
        rows += [
            Metric(f"{key}.n_without", f"{where}: N without transfer",
                   lambda s, get=get: get(s).n_without, without, "thesis Table 5.4"),
            Metric(f"{key}.n_with", f"{where}: N with transfer",
                   lambda s, get=get: get(s).n_with, with_, "thesis Table 5.4"),
            Metric(f"{key}.found", f"{where}: seeds that found the functional pair",
                   lambda s, get=get, can=can: found_pair(get(s), can), 1.0, "the can file"),
        ]
    return rows


def claims(config: Config) -> list[Claim]:
    """Transfer needs fewer actions than learning without it, on every can after the first."""
    return [Claim(f"Transfer opens {can} ({perception}) in fewer actions than Algorithm 4 "
                  "(Table 5.4)", f"{perception}.{can}.n_with", f"{perception}.{can}.n_without",
                  "less")
            for perception, can in product(config.perceptions, config.cans[1:])]


def listings(config: Config, seeds: Sequence[Result]) -> str:
    """Table 5.4 as the thesis prints it, per perception: N without and with transfer (means
    over the seeds), the most frequent source, pair and branch, whether transfer never took
    more actions, beside the thesis's row."""
    lines = []
    for perception in config.perceptions:
        rows = []
        for can in config.cans:
            runs = [seed.perceptions[perception][can] for seed in seeds]
            found = sum((r.part, r.action) == true_pair(can) for r in runs)
            part, action = most_frequent([(r.part, r.action) for r in runs])
            thesis = THESIS.get(can, ("-", "-", "-"))
            rows.append([can, f"{sum(r.n_without for r in runs) / len(runs):.1f}",
                         f"{sum(r.n_with for r in runs) / len(runs):.1f}",
                         most_frequent([r.source for r in runs]) or "-",
                         f"{action}({part}) ({found}/{len(runs)})",
                         most_frequent([r.branch for r in runs]),
                         all(r.n_with <= r.n_without for r in runs),
                         f"{thesis[0]}, {thesis[1] or '-'}, {thesis[2] or '-'}"])
        lines += [f"## Table 5.4 ({perception} perception)", "", markdown_table(
            ["can", "N without", "N with transfer", "source", "pair found (of seeds)", "branch",
             "never worse", "thesis (N, N_tran, source)"], rows), ""]
    return "\n".join(lines)


def figures(config: Config, seeds: Sequence[Result]) -> list[Figure]:
    x = list(range(1, len(config.cans) + 1))
    panels = []
    for perception in config.perceptions:
        def runs(field: str, perception: str = perception) -> list[list[int]]:
            return [[getattr(seed.perceptions[perception][c], field) for c in config.cans]
                    for seed in seeds]

        panels.append(Panel(f"can ({', '.join(config.cans)})", f"actions ({perception})",
                            [Series("without transfer (Algorithm 4)", x, runs("n_without")),
                             Series("with transfer (Algorithm 6)", x, runs("n_with"))],
                            [Reference(3, "thesis: o3 with transfer at most 3")]))
    return [Figure("actions", "Table 5.4: actions to open each can", panels)]


STUDY = Study(
    name="ch5-transfer",
    description="Table 5.4: actions to open each can without and with transfer (o1..o5, "
                "then slide and pedal)",
    config=Config, result=Result, run=run, metrics=metrics, claims=claims, figures=figures,
    listings=listings, default_seeds=5, deviations=CH5_DEVIATIONS,
    quick={"cans": ("o1", "o3"), "perceptions": ("truth",)},
    headline=(*(f"truth.{can}.n_without" for can in THESIS_CANS),
              *(f"truth.{can}.n_with" for can in THESIS_CANS[1:]), "truth.pedal.n_with"),
    notes="""\
**Setup**: each seed starts from an empty database and presents the cans in order; each can
is learned with transfer (Algorithm 5 picks the source by shared `above` relations among the
known cans whose functional part looks like one of the can's parts, Algorithm 6 transfers)
and, on a fresh copy of the can with the same seed, without (Algorithm 4: every part × action
type, n = 5, a pair stops after three samples once its model settles as moving nothing). N
counts every physical action, goal-directed ones included. The goal is an opening of 0.1 m
(eq. 5.9). See docs/results/ch5.md for what differs from the thesis and why.""",
)
