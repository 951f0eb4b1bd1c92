"""VARIANT stop criteria for ``ch4-exploration``, reported beside the thesis's (4.10), never
instead of it (issue 10: the owner decides whether any replaces it).

Every run records its whole TD-error series once; each criterion of
``behaviours.learners.convergence`` is evaluated on that series, so the variants need no
extra simulation and judge exactly the runs the thesis's test judged. The page keeps the
thesis's numbers as its main rows; the variants go into a separate, clearly titled table.
"""

from __future__ import annotations

import statistics
from collections.abc import Sequence

from behaviours.learners.convergence import VARIANTS, first_convergence
from robot.reproduce.framework import markdown_table
from robot.reproduce.studies.common.ch4 import (
    CONFIGURATIONS,
    METHODS,
    Exploration,
    ExplorationConfig,
    ExplorationRun,
    median_or_none,
)

THESIS = "thesis"


def criterion_step(run: ExplorationRun, criterion: str,
                   config: ExplorationConfig) -> int | None:
    """The first step at which ``criterion`` held in one run: the thesis's as Algorithm 3
    tested it online, a variant on the run's recorded TD errors (the config's N and ε)."""
    if criterion == THESIS:
        return run.converged_at
    return first_convergence(run.td_errors, criterion, config.window, config.tolerance)


EXPLANATION = """\
## VARIANT stop criteria — NOT the thesis's (4.10)

Each row below departs from the thesis: it is NOT eq. 4.10 and is not what Algorithm 3 runs.
The thesis's test is the first row of each configuration (and the page's "converged (4.10)"
rows); the variants are reported beside it so the owner can decide
whether any should replace it (issue 10). All are evaluated on the same recorded TD errors
δ^k of the same runs, with δ̄^k = (1/N) Σ_{i=k−N+1..k} |δ^i| (4.11) and the N and ε below:

- **thesis (4.10)**: first k ≥ N + 1 with |δ̄^k − δ̄^(k−1)| < ε.
- **after-transient** (variant): first k ≥ 2N + 1 with |δ̄^k − δ̄^(k−1)| < ε — (4.10) judged
  only on averages over steps after the N random ones ("NAO performed the first 20 actions
  randomly. Then, it continued random exploration or switched to the active learning mode").
- **sustained** (variant): first k with |δ̄^j − δ̄^(j−1)| < ε for every j = k−N+1..k — (4.10)
  at N consecutive steps ("terminates when the RL almost stops, i.e., there is not much change
  in the actor-critic RL component"; random exploration "occasionally runs into situations
  with high prediction errors so that the TD errors would hardly converge").
- **window-to-window** (variant): first k ≥ 2N with |δ̄^k − δ̄^(k−N)| < ε — two consecutive,
  non-overlapping window averages agree (the averaged error "is expected to decrease and
  become stable"; Figs 4.6–4.9 plot δ̄).

How they were chosen: from the thesis's wording only, before any was computed on any run,
under one rule — keep N and ε, change only when or what (4.10) compares, add no new constant
(every new length is N). Not included: ε relative to the reward's scale (our s_o and e_o
already have the thesis's scale, so it would be about the thesis's ε), and δ̄ below a level
(the thesis gives none; one picked now would be picked knowing δ̄ at N_s above).
"Sooner / tie / later": seeds where active met the criterion before random (a run that never
met it counts as later than any that did; both never is a tie). "δ̄ where it held": median
over seeds of δ̄^k at the step the criterion first held.
"""


def variant_listing(config: ExplorationConfig, seeds: Sequence[Exploration]) -> str:
    """The explanation and one table: every criterion × configuration, active beside random."""
    rows = []
    for name in CONFIGURATIONS:
        for criterion in (THESIS, *VARIANTS):
            runs = [{method: seed.of(name, method) for method in METHODS} for seed in seeds]
            steps = [{method: criterion_step(run[method], criterion, config)
                      for method in METHODS} for run in runs]
            label = "thesis (4.10)" if criterion == THESIS else f"{criterion} (VARIANT)"
            rows.append([name, label,
                         *(_counted([s[method] for s in steps]) for method in METHODS),
                         _sooner(steps),
                         " / ".join(_level(runs, steps, method) for method in METHODS)])
    headers = ["configuration", "criterion", "active: converged, median step",
               "random: converged, median step", "active sooner / tie / later",
               "δ̄ where it held, active / random"]
    return (EXPLANATION + f"\nHere N = {config.window}, ε = {config.tolerance:g}.\n\n"
            + markdown_table(headers, rows))


def _counted(steps: list[int | None]) -> str:
    met = [step for step in steps if step is not None]
    median = median_or_none(met)
    return f"{len(met)}/{len(steps)}, " + ("—" if median is None else f"{median:g}")


def _sooner(steps: list[dict]) -> str:
    """Seeds where active met the criterion sooner / at the same step / later than random."""
    never = float("inf")
    pairs = [(s["active"] or never, s["random"] or never) for s in steps]
    return " / ".join(str(sum(test(a, r) for a, r in pairs)) for test in (
        lambda a, r: a < r, lambda a, r: a == r, lambda a, r: a > r))


def _level(runs: list[dict], steps: list[dict], method: str) -> str:
    """The median δ̄ at the step the criterion first held, over the seeds where it did."""
    levels = [run[method].averaged[step[method] - 1]
              for run, step in zip(runs, steps, strict=True) if step[method] is not None]
    return f"{statistics.median(levels):.4f}" if levels else "—"
