"""``ch5-transfer``: thesis Table 5.4, learning the cans with and without transfer.

Per seed, in truth and in camera perception: the cans o1..o5 presented in the thesis's order
(then the two new mechanisms, ``slide`` and ``pedal``), each learned with Algorithm 6 from the
cans before it and, for N without transfer, with Algorithm 4 (``robot/transfer_study.py``).
"""

from __future__ import annotations

from robot.reproduce.framework import (
    Comparison,
    Figure,
    Panel,
    Progress,
    Reference,
    Reproduction,
    Series,
    markdown_table,
    mean_and_std,
)

CANS = ("o1", "o2", "o3", "o4", "o5", "slide", "pedal")
QUICK_CANS = ("o1", "o3")
PERCEPTIONS = ("truth", "camera")
THESIS = {"o1": (36, None, None), "o2": (65, 29, "o1"), "o3": (53, 1, "o1"),
          "o4": (83, 3, "o2"), "o5": (80, 11, "o2")}
"""Table 5.4 as printed: (N without, N with transfer, source)."""


def run_seed(seed: int, scale: float, progress: Progress) -> dict:
    """One seed: every can in truth and in camera perception (a quick run: o1, o3 in truth)."""
    from robot.transfer_study import transfer_seed

    full = scale >= 0.5
    cans, perceptions = (CANS, PERCEPTIONS) if full else (QUICK_CANS, ("truth",))
    result: dict = {"seed": seed}
    for index, perception in enumerate(perceptions):
        result[perception] = transfer_seed(seed, cans, perception)
        progress((index + 1) / len(perceptions))
    return result


def summarize(seeds: list[dict]) -> dict:
    """Per can (truth perception): n_without, n_with (means), the most frequent source, part,
    action (and branch, found, never_worse); each can's camera numbers under "camera"."""
    from robot.transfer_study import transfer_summary

    summary = transfer_summary([seed["truth"] for seed in seeds])
    if all("camera" in seed for seed in seeds):
        camera = transfer_summary([seed["camera"] for seed in seeds])
        for can, entry in summary.items():
            entry["camera"] = camera[can]
    return summary


def compare(summary: dict, seeds: list[dict]) -> list[Comparison]:
    rows = []
    for perception in PERCEPTIONS:
        if perception not in seeds[0]:
            continue
        for can in seeds[0][perception]:
            runs = [seed[perception][can] for seed in seeds]
            without, without_sd = mean_and_std([r["n_without"] for r in runs])
            with_, with_sd = mean_and_std([r["n_with"] for r in runs])
            thesis = THESIS.get(can, (None, None, None))
            rows.append(Comparison(f"{can} N without transfer ({perception})", without,
                                   without_sd, thesis[0], "thesis Table 5.4"))
            if can != "o1":
                rows.append(Comparison(f"{can} N with transfer ({perception})", with_, with_sd,
                                       thesis[1], "thesis Table 5.4"))
    return rows


def listings(summary: dict, seeds: list[dict]) -> str:
    """Table 5.4 as the thesis prints it: per can (truth perception) N without and with
    transfer, the source, the pair found, Algorithm 6's branch, beside the thesis's row."""
    rows = []
    for can, s in summary.items():
        thesis = THESIS.get(can, ("-", "-", "-"))
        rows.append([can, f"{s['n_without']:.1f}", f"{s['n_with']:.1f}", s["source"] or "-",
                     f"{s['action']}({s['part']}) ({s['found']}/{len(seeds)})", s["branch"],
                     s["never_worse"], f"{thesis[0]}, {thesis[1] or '-'}, {thesis[2] or '-'}"])
    return "\n".join(["## Table 5.4 (truth perception)", "", markdown_table(
        ["can", "N without", "N with transfer", "source", "pair found (of seeds)", "branch",
         "never worse", "thesis (N, N_tran, source)"], rows)])


def figures(seeds: list[dict]) -> list[Figure]:
    cans = list(seeds[0]["truth"])
    x = list(range(1, len(cans) + 1))
    panels = []
    for perception in PERCEPTIONS:
        if perception not in seeds[0]:
            continue
        panels.append(Panel(
            f"can ({', '.join(cans)})", f"actions ({perception})",
            [Series("without transfer (Algorithm 4)", x,
                    [[seed[perception][c]["n_without"] for c in cans] for seed in seeds]),
             Series("with transfer (Algorithm 6)", x,
                    [[seed[perception][c]["n_with"] for c in cans] for seed in seeds])],
            [Reference(3, "thesis: o3 with transfer at most 3")]))
    return [Figure("actions", "Table 5.4: actions to open each can", panels)]


REPRODUCTION = Reproduction(
    name="ch5-transfer",
    description="Table 5.4: actions to open each can without and with transfer (o1..o5, "
                "then slide and pedal)",
    run_seed=run_seed, summarize=summarize, compare=compare, figures=figures,
    listings=listings,
    quick_scale=0.1, default_seeds=5,
    notes="""\
**Setup**: each seed starts from an empty database and presents o1, o2, o3, o4, o5, slide,
pedal in that order; each can is learned with transfer (Algorithm 5 picks the source by
shared `above` relations among the known cans whose functional part looks like one of the
can's parts, Algorithm 6 transfers) and, on a fresh copy of the can with the same seed,
without (Algorithm 4: every part × action type, n = 5, a pair stops after three samples once
its model settles as moving nothing). N counts every physical action, goal-directed ones
included. The goal is an opening of 0.1 m (eq. 5.9). See docs/results/ch5.md for what differs
from the thesis and why.""",
)
