"""``ch5-baseline``: thesis Table 5.3 and the N-without column of Table 5.4 (Algorithm 4)."""

from __future__ import annotations

from collections.abc import Sequence
from itertools import product

from robot.reproduce.framework import (
    Claim,
    Figure,
    Metric,
    Panel,
    Progress,
    SeedResult,
    Series,
    Study,
    in_turn,
    markdown_table,
)
from robot.reproduce.studies.common.ch5 import (
    CH5_DEVIATIONS,
    BaselineRow,
    PairModel,
    PartLearningConfig,
    baseline_run,
    found_pair,
)

THESIS_N = {"o1": 36, "o2": 65, "o3": 53, "o4": 83, "o5": 80}
THESIS_MODELS = {"o1": ("lid", "extend_arm", 0.574, 1.833),
                 "o2": ("handle", "lift_up", 1.866, 0.508),
                 "o3": ("lid", "extend_arm", 0.642, 2.014),
                 "o4": ("handle", "lift_up", 2.891, 0.590),
                 "o5": ("handle", "contract_arm", 0.240, 1.923)}
"""Table 5.3's functional pairs: (part, action, slope of ĝ, slope of ĥ)."""
THESIS_MOVING = {"o1": (), "o2": (("handle", "extend_arm"), ("handle", "contract_arm")),
                 "o3": (("body", "extend_arm"),), "o4": (),
                 "o5": (("handle", "sweep_left"), ("handle", "lift_up"), ("lid", "extend_arm"))}
"""Table 5.3's non-functional pairs whose ĝ moves the part by a centimetre or more within Θ:
o2's handle pushed (0.588θ) and pulled (0.452θ), o3's body pushed (0.659θ), o5's handle swept
(3.205θ; the thesis does not say which way) and lifted (0.522θ), o5's lid pushed (1.070θ).
o4's handle pushed (0.069θ: under 7 mm) is not counted."""
MIN_DISPLACEMENT = 0.01
"""Algorithm 4's ``min_displacement`` (m): a pair whose ĝ predicts less nowhere in Θ moves
nothing."""
THETA_MAX = 0.1
"""The largest θ (m) of every action type."""


class Result(SeedResult):
    perceptions: dict[str, dict[str, BaselineRow]]
    """perception -> can -> Algorithm 4's run."""


def run(config: PartLearningConfig, seed: int, progress: Progress) -> Result:
    """Algorithm 4 on every can, in every perception."""
    return Result(perceptions={perception: baseline_run(seed, config, perception)
                               for perception in in_turn(config.perceptions, progress)})


def _slope(row: BaselineRow, which: str) -> float | None:
    """The slope of ĝ or ĥ of the pair the run found, None if it found none."""
    for model in row.models:
        if (model.part, model.action) == (row.part, row.action):
            return getattr(model, which)[1]
    return None


def moving_nonfunctional(row: BaselineRow) -> list[PairModel]:
    """The pairs other than the one found whose ĝ moves the part by at least
    ``MIN_DISPLACEMENT`` somewhere in 0 < θ <= ``THETA_MAX`` (what Algorithm 4 counts as
    moving)."""
    def moves(model: PairModel) -> bool:
        intercept, slope = model.g
        return max(abs(intercept), abs(intercept + slope * THETA_MAX)) >= MIN_DISPLACEMENT

    return [m for m in row.models if (m.part, m.action) != (row.part, row.action) and moves(m)]


def metrics(config: PartLearningConfig) -> list[Metric[Result]]:
    rows: list[Metric[Result]] = []
    for perception, can in product(config.perceptions, config.cans):
        def get(seed: Result, p: str = perception, c: str = can) -> BaselineRow:
            return seed.perceptions[p][c]

        key, where = f"{perception}.{can}", f"{can} ({perception})"
        rows += [
            Metric(f"{key}.n_without", f"{where}: N without transfer",
                   lambda s, get=get: get(s).n, THESIS_N.get(can), "thesis Table 5.4"),
            Metric(f"{key}.found", f"{where}: seeds that found the functional pair",
                   lambda s, get=get, can=can: found_pair(get(s), can), 1.0, "the can file"),
            Metric(f"{key}.moving_nonfunctional", f"{where}: non-functional pairs that move "
                   "the part", lambda s, get=get: float(len(moving_nonfunctional(get(s)))),
                   None if can not in THESIS_MOVING else float(len(THESIS_MOVING[can])),
                   "thesis Table 5.3 (the pairs it lists)"),
        ]
        if can in THESIS_MODELS:
            part, action, g, h = THESIS_MODELS[can]
            rows += [Metric(f"{key}.{which}_slope", f"{where}: {action}({part}) {symbol} slope",
                            lambda s, get=get, which=which: _slope(get(s), which), reference,
                            "thesis Table 5.3 (NAO, image metres)")
                     for which, symbol, reference in (("g", "ĝ", g), ("h", "ĥ", h))]
    return rows


def claims(config: PartLearningConfig) -> list[Claim]:
    return [Claim(f"Algorithm 4 learns {can} ({perception}) in Table 5.4's number of actions, "
                  f"{THESIS_N[can]}", f"{perception}.{can}.n_without", float(THESIS_N[can]),
                  "same")
            for perception, can in product(config.perceptions, config.cans)
            if can in THESIS_N]


def listings(config: PartLearningConfig, seeds: Sequence[Result]) -> str:
    """Table 5.3 of the first seed in the first perception: ĝ(θ) = b + cθ and ĥ(e) = d + e·e
    of every pair tried, the functional pair in bold."""
    perception = config.perceptions[0]
    rows = []
    for can, entry in seeds[0].perceptions[perception].items():
        for m in entry.models:
            bold = "**" if (m.part, m.action) == (entry.part, entry.action) else ""
            rows.append([can, m.part, f"{bold}{m.action}{bold}", m.n,
                         f"{m.g[0]:+.3f} {m.g[1]:+.3f}θ", f"{m.h[0]:+.3f} {m.h[1]:+.3f}e"])
    moving = []
    for can, entry in seeds[0].perceptions[perception].items():
        thesis = ", ".join(f"{a}({p})" for p, a in THESIS_MOVING.get(can, ())) or "—"
        found = ", ".join(f"{m.action}({m.part})" for m in moving_nonfunctional(entry)) or "—"
        moving.append([can, found, thesis if can in THESIS_MOVING else "—"])
    return "\n".join([
        f"## Table 5.3 (the first seed, {perception} perception)", "",
        "ĝ(θ) = b + cθ (eq. 5.16) and ĥ(e_ψ) = d + e·e_ψ (eq. 5.17) of every pair tried; the "
        "functional pair in bold.", "",
        markdown_table(["can", "part", "action", "n", "ĝ", "ĥ"], rows), "",
        f"## Non-functional pairs that move their part (the first seed, {perception})", "",
        f"Pairs other than the functional one whose ĝ moves the part by {MIN_DISPLACEMENT} m "
        f"or more for some θ ≤ {THETA_MAX} m: Algorithm 4 samples them n = 5 times instead of "
        "stopping after 3, and they count in N.", "",
        markdown_table(["can", "moving non-functional pairs (here)", "thesis Table 5.3"],
                       moving)])


def figures(config: PartLearningConfig, seeds: Sequence[Result]) -> list[Figure]:
    x = list(range(1, len(config.cans) + 1))
    return [Figure("actions", "Algorithm 4: actions to learn each can", [
        Panel(f"can ({', '.join(config.cans)})", f"actions without transfer ({perception})",
              [Series("Algorithm 4", x, [[seed.perceptions[perception][c].n
                                          for c in config.cans] for seed in seeds])])
        for perception in config.perceptions])]


STUDY = Study(
    name="ch5-baseline",
    description="Table 5.3: part models of every part x action and N without transfer "
                "(Algorithm 4) for o1..o5",
    config=PartLearningConfig, result=Result, run=run, metrics=metrics, claims=claims,
    figures=figures, listings=listings, default_seeds=5, deviations=CH5_DEVIATIONS,
    quick={"cans": ("o1",), "perceptions": ("truth",)},
    headline=("truth.o2.n_without", "truth.o5.n_without", "truth.o2.found", "truth.o4.found",
              "truth.o5.found", "truth.o5.moving_nonfunctional"),
    notes="""\
**Setup**: Algorithm 4 on each can: every part × action type with random θ in (0, 0.1] m,
n = 5 samples per pair, a pair stopping after three once its ĝ and ĥ settle (eq. 5.19) and
predict no displacement of the part; then the pair and θ chosen by eq. 5.11/5.12 act until the
can opens 0.1 m. Every pair's ĝ and ĥ are in the JSON. The slopes differ from the thesis's
because the simulated cans are not the NAO's (θ moves the hand in metres; displacement is
measured by eq. 5.15 from the image).""",
)
