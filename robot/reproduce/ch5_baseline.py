"""``ch5-baseline``: thesis Table 5.3 and the N-without column of Table 5.4 (Algorithm 4)."""

from __future__ import annotations

from robot.reproduce.framework import (
    Comparison,
    Figure,
    Panel,
    Progress,
    Reproduction,
    Series,
    markdown_table,
    mean_and_std,
)

CANS = ("o1", "o2", "o3", "o4", "o5")
PERCEPTIONS = ("truth", "camera")
THESIS_N = {"o1": 36, "o2": 65, "o3": 53, "o4": 83, "o5": 80}
THESIS_MODELS = {"o1": ("lid", "extend_arm", 0.574, 1.833),
                 "o2": ("handle", "lift_up", 1.866, 0.508),
                 "o3": ("lid", "extend_arm", 0.642, 2.014),
                 "o4": ("handle", "lift_up", 2.891, 0.590),
                 "o5": ("handle", "contract_arm", 0.240, 1.923)}
"""Table 5.3's functional pairs: (part, action, slope of ĝ, slope of ĥ)."""


def run_seed(seed: int, scale: float, progress: Progress) -> dict:
    """One seed: Algorithm 4 on every can, truth and camera (a quick run: o1 in truth)."""
    from robot.transfer_study import baseline_seed

    cans, perceptions = (CANS, PERCEPTIONS) if scale >= 0.5 else (("o1",), ("truth",))
    result: dict = {"seed": seed}
    for index, perception in enumerate(perceptions):
        result[perception] = baseline_seed(seed, cans, perception)
        progress((index + 1) / len(perceptions))
    return result


def summarize(seeds: list[dict]) -> dict:
    from robot.transfer_study import baseline_summary

    summary = baseline_summary([seed["truth"] for seed in seeds])
    if all("camera" in seed for seed in seeds):
        camera = baseline_summary([seed["camera"] for seed in seeds])
        for can, entry in summary.items():
            entry["camera"] = camera[can]
    return summary


def _functional_slopes(run: dict) -> tuple[float, float] | None:
    """(ĝ slope, ĥ slope) of the pair the run found."""
    for model in run["models"]:
        if (model["part"], model["action"]) == (run["part"], run["action"]):
            return model["g"][1], model["h"][1]
    return None


def compare(summary: dict, seeds: list[dict]) -> list[Comparison]:
    rows = []
    for perception in PERCEPTIONS:
        if perception not in seeds[0]:
            continue
        for can in seeds[0][perception]:
            runs = [seed[perception][can] for seed in seeds]
            n, n_sd = mean_and_std([r["n"] for r in runs])
            rows.append(Comparison(f"{can} N without transfer ({perception})", n, n_sd,
                                   THESIS_N.get(can), "thesis Table 5.4"))
            slopes = [s for s in (_functional_slopes(r) for r in runs) if s is not None]
            if slopes and can in THESIS_MODELS:
                part, action, g, h = THESIS_MODELS[can]
                for index, (what, reference) in enumerate((("ĝ slope", g), ("ĥ slope", h))):
                    value, spread = mean_and_std([s[index] for s in slopes])
                    rows.append(Comparison(f"{can} {action}({part}) {what} ({perception})",
                                           value, spread, reference,
                                           "thesis Table 5.3 (NAO, image metres)"))
    return rows


def listings(summary: dict, seeds: list[dict]) -> str:
    """Table 5.3 of the first seed in truth perception: ĝ(θ) = b + cθ and ĥ(e) = d + e·e of
    every pair tried, the functional pair in bold."""
    first = seeds[0]
    lines = [f"## Table 5.3 (seed {first['seed']}, truth perception)", "",
             "ĝ(θ) = b + cθ (eq. 5.16) and ĥ(e_ψ) = d + e·e_ψ (eq. 5.17) of every pair tried; "
             "the functional pair in bold.", ""]
    rows = []
    for can, entry in first["truth"].items():
        for m in entry["models"]:
            bold = "**" if (m["part"], m["action"]) == (entry["part"], entry["action"]) else ""
            rows.append([can, m["part"], f"{bold}{m['action']}{bold}", m["n"],
                         f"{m['g'][0]:+.3f} {m['g'][1]:+.3f}θ",
                         f"{m['h'][0]:+.3f} {m['h'][1]:+.3f}e"])
    lines.append(markdown_table(["can", "part", "action", "n", "ĝ", "ĥ"], rows))
    return "\n".join(lines)


def figures(seeds: list[dict]) -> list[Figure]:
    cans = list(seeds[0]["truth"])
    x = list(range(1, len(cans) + 1))
    panels = [Panel(f"can ({', '.join(cans)})", f"actions without transfer ({p})",
                    [Series("Algorithm 4", x, [[seed[p][c]["n"] for c in cans]
                                               for seed in seeds])])
              for p in PERCEPTIONS if p in seeds[0]]
    return [Figure("actions", "Algorithm 4: actions to learn each can", panels)]


REPRODUCTION = Reproduction(
    name="ch5-baseline",
    description="Table 5.3: part models of every part x action and N without transfer "
                "(Algorithm 4) for o1..o5",
    run_seed=run_seed, summarize=summarize, compare=compare, figures=figures,
    listings=listings,
    quick_scale=0.1, default_seeds=5,
    notes="""\
**Setup**: Algorithm 4 on each can: every part × action type with random θ in (0, 0.1] m,
n = 5 samples per pair, a pair stopping after three once its ĝ and ĥ settle (eq. 5.19) and
predict no displacement of the part; then the pair and θ chosen by eq. 5.11/5.12 act until the
can opens 0.1 m. Every pair's ĝ and ĥ are in the JSON. The slopes differ from the thesis's
because the simulated cans are not the NAO's (θ moves the hand in metres; displacement is
measured by eq. 5.15 from the image).""",
)
