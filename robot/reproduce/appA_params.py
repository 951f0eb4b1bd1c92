"""``appA-params``: the thesis's XCS settings (Table 7.1) on Woods2 and on the 6-multiplexer.

Table 7.1 was chosen for NAO experiments of a few dozen trials ("the population size limit and
GA threshold are both decreased due to much less experiment trials compared with the thousands
of trials in woods2"). This runs it on the classic problems as a regression test of those
settings — it must run without errors — and, beside it, the same settings with the
population size the problems are known to need (N = 800 in Woods2, 400 on the 6-multiplexer),
which shows what N = 100 costs there.
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
    mean_and_std,
)
from robot.reproduce.lcs_experiments import multiplexer_experiment, woods_experiment
from robot.reproduce.lcs_problems import WOODS2, WOODS2_CODES
from robot.reproduce.xcs_woods2 import woods_figure, woods_summary

TABLE_7_1 = {
    "N": 100, "gamma": 0.7, "beta_p": 0.2, "beta_e": 0.2, "beta_f": 0.2, "chi": 0.8,
    "mu": 0.04, "epsilon_0": 10.0, "alpha": 0.1, "nu": 5.0, "prediction_init": 10.0,
    "error_init": 0.0, "fitness_init": 0.01, "p_hash": 0.6, "theta_ga": 5, "theta_del": 20,
}
"""Thesis Table 7.1; the rest (θsub = 20, δ = 0.1, GA subsumption) are XCS's defaults."""
LARGER_N = {"woods2": 800, "mux6": 400}
"""The population sizes Wilson used on these problems."""
TRIAL_STEP_LIMIT = 20
"""Table 7.1's N_s."""
PROBLEMS = {"woods2": 4_000, "mux6": 10_000}
RUNS = ("woods2", "woods2_larger_n", "mux6", "mux6_larger_n")
WORK = {"woods2": 0.4, "woods2_larger_n": 0.4, "mux6": 0.1, "mux6_larger_n": 0.1}
"""Rough share of a seed's time each run takes (for the progress bar)."""


def run_seed(seed: int, scale: float, progress: Progress) -> dict:
    result, done = {}, 0.0
    for run in RUNS:
        problem = run.removesuffix("_larger_n")
        params = {**TABLE_7_1, "N": LARGER_N[problem]} if run != problem else TABLE_7_1
        problems = max(100, round(PROBLEMS[problem] * scale))

        def report(fraction: float, done: float = done, share: float = WORK[run]) -> None:
            progress(done + share * fraction)

        if problem == "woods2":
            result[run] = woods_experiment(WOODS2, WOODS2_CODES, problems, params, seed,
                                           report, TRIAL_STEP_LIMIT)
        else:
            result[run] = multiplexer_experiment(2, problems, params, seed, report)
        done += WORK[run]
    return result


def _mux_summary(runs: list[dict]) -> dict:
    accuracy, accuracy_sd = mean_and_std([run["final_accuracy"] for run in runs])
    reached = [run["problems_to_99"] for run in runs]
    problems, problems_sd = mean_and_std(reached)
    return {"final_accuracy": accuracy, "final_accuracy_sd": accuracy_sd,
            "problems_to_99": problems if None not in reached else None,
            "problems_to_99_sd": problems_sd if None not in reached else None,
            "seeds_reaching_99": sum(value is not None for value in reached),
            "seeds": len(runs)}


def summarize(seeds: list[dict]) -> dict:
    return {run: (woods_summary if run.startswith("woods2") else _mux_summary)(
        [seed[run] for seed in seeds]) for run in RUNS}


def compare(summary: dict, seeds: list[dict]) -> list[Comparison]:
    rows = []
    for run, label in (("woods2", "N = 100"), ("woods2_larger_n", "N = 800")):
        woods = summary[run]
        rows += [
            Comparison(f"Woods2, Table 7.1 with {label}: steps to food at the end",
                       woods["final_steps"], woods["final_steps_sd"], woods["optimum"],
                       "optimum over the map (no thesis value: Table 7.1 served NAO tasks)"),
            Comparison(f"Woods2, Table 7.1 with {label}: macro-classifiers at the end",
                       woods["final_macro_classifiers"], woods["final_macro_classifiers_sd"]),
        ]
    for run, label in (("mux6", "N = 100"), ("mux6_larger_n", "N = 400")):
        mux = summary[run]
        rows += [
            Comparison(f"6-multiplexer, Table 7.1 with {label}: fraction correct, last 50 "
                       "exploit problems", mux["final_accuracy"], mux["final_accuracy_sd"], 1.0,
                       "a perfect score (no thesis value)"),
            Comparison(f"6-multiplexer, Table 7.1 with {label}: explore problems until 50/50 "
                       f"correct for good ({mux['seeds_reaching_99']}/{mux['seeds']} seeds got "
                       "there)", mux["problems_to_99"], mux["problems_to_99_sd"]),
        ]
    return rows


def figures(seeds: list[dict]) -> list[Figure]:
    woods = {"Table 7.1 (N = 100)": [seed["woods2"] for seed in seeds],
             "Table 7.1 with N = 800": [seed["woods2_larger_n"] for seed in seeds]}
    mux = {"Table 7.1 (N = 100)": [seed["mux6"] for seed in seeds],
           "Table 7.1 with N = 400": [seed["mux6_larger_n"] for seed in seeds]}
    x = seeds[0]["mux6"]["problems"]
    return [
        woods_figure(woods, "woods2", "Table 7.1's XCS in Woods2 (θGA = 5, P# = 0.6, N_s = 20)",
                     ylim=(0.0, TRIAL_STEP_LIMIT + 1)),
        Figure("mux6", "Table 7.1's XCS on the 6-multiplexer (θGA = 5, P# = 0.6)", [
            Panel("explore problems", "fraction correct (last 50 exploit problems)",
                  [Series(label, x, [run["accuracy"] for run in runs])
                   for label, runs in mux.items()],
                  [Reference(1.0, "100%")], ylim=(0.4, 1.02)),
            Panel("explore problems", "population size (macro-classifiers)",
                  [Series(label, x, [run["macro_classifiers"] for run in runs])
                   for label, runs in mux.items()]),
        ]),
    ]


REPRODUCTION = Reproduction(
    name="appA-params",
    description="The thesis's XCS settings (Table 7.1) on Woods2 and the 6-multiplexer, as a "
                "regression test of those settings",
    run_seed=run_seed, summarize=summarize, compare=compare, figures=figures,
    notes=f"""\
**Setup**: Table 7.1 — N = 100, γ = 0.7, β_p = β_ε = β_F = 0.2, χ = 0.8, μ = 0.04, ε0 = 10,
α = 0.1, ν = 5, p⁰ = 10, ε⁰ = 0, F⁰ = 0.01, P# = 0.6, θGA = 5, θdel = 20 — with the trial step
limit N_s = {TRIAL_STEP_LIMIT} on Woods2 (the same map, sensing and protocol as `xcs-woods2`)
and on the 6-multiplexer (as `xcs-mux`, reward 1000/0). Not given by the table: θsub = 20,
δ = 0.1, GA subsumption on. The thesis reports no numbers for these problems; the references
are the problems' best possible values. The "with N = 800 / 400" runs change only N, to the
population sizes Wilson used: the difference between the two is what N = 100 costs.""",
)
