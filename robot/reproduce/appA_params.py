"""``appA-params``: the thesis's XCS settings (Table 7.1) on Woods2 and on the 6-multiplexer.

Table 7.1 was chosen for NAO experiments of a few dozen trials ("the population size limit and
GA threshold are both decreased due to much less experiment trials compared with the thousands
of trials in woods2"). This runs it on the classic problems as a regression test of those
settings: it must run without errors, and it shows what N = 100 and θGA = 5 cost there.
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
TRIAL_STEP_LIMIT = 20
"""Table 7.1's N_s."""
WOODS2_PROBLEMS = 4_000
MUX6_PROBLEMS = 10_000


def run_seed(seed: int, scale: float, progress: Progress) -> dict:
    woods_problems = max(100, round(WOODS2_PROBLEMS * scale))
    mux_problems = max(100, round(MUX6_PROBLEMS * scale))
    woods = woods_experiment(WOODS2, WOODS2_CODES, woods_problems, TABLE_7_1, seed,
                             lambda fraction: progress(0.8 * fraction), TRIAL_STEP_LIMIT)
    mux = multiplexer_experiment(2, mux_problems, TABLE_7_1, seed,
                                 lambda fraction: progress(0.8 + 0.2 * fraction))
    return {"woods2": woods, "mux6": mux}


def summarize(seeds: list[dict]) -> dict:
    woods = woods_summary([seed["woods2"] for seed in seeds])
    runs = [seed["mux6"] for seed in seeds]
    accuracy, accuracy_sd = mean_and_std([run["final_accuracy"] for run in runs])
    reached = [run["problems_to_99"] for run in runs]
    problems, problems_sd = mean_and_std(reached)
    return {"woods2": woods, "mux6": {
        "final_accuracy": accuracy, "final_accuracy_sd": accuracy_sd,
        "problems_to_99": problems if None not in reached else None,
        "problems_to_99_sd": problems_sd if None not in reached else None,
        "seeds_reaching_99": sum(value is not None for value in reached), "seeds": len(runs)}}


def compare(summary: dict, seeds: list[dict]) -> list[Comparison]:
    woods, mux = summary["woods2"], summary["mux6"]
    return [
        Comparison("Woods2: steps to food at the end (Table 7.1, N_s = 20)",
                   woods["final_steps"], woods["final_steps_sd"], woods["optimum"],
                   "optimum over the map (no thesis value: Table 7.1 served NAO tasks)"),
        Comparison("Woods2: macro-classifiers at the end", woods["final_macro_classifiers"],
                   woods["final_macro_classifiers_sd"]),
        Comparison("6-multiplexer: fraction correct, last 50 exploit problems",
                   mux["final_accuracy"], mux["final_accuracy_sd"], 1.0,
                   "a perfect score (no thesis value)"),
        Comparison(f"6-multiplexer: explore problems until 50/50 correct for good "
                   f"({mux['seeds_reaching_99']}/{mux['seeds']} seeds got there)",
                   mux["problems_to_99"], mux["problems_to_99_sd"]),
    ]


def figures(seeds: list[dict]) -> list[Figure]:
    runs = [seed["mux6"] for seed in seeds]
    x = runs[0]["problems"]
    return [
        woods_figure([seed["woods2"] for seed in seeds], "woods2",
                     "Table 7.1's XCS in Woods2 (N = 100, θGA = 5, P# = 0.6)"),
        Figure("mux6", "Table 7.1's XCS on the 6-multiplexer (N = 100)", [
            Panel("explore problems", "fraction correct (last 50 exploit problems)",
                  [Series("goalagent XCS", x, [run["accuracy"] for run in runs])],
                  [Reference(1.0, "100%")], ylim=(0.4, 1.02)),
            Panel("explore problems", "population size (macro-classifiers)",
                  [Series("goalagent XCS", x, [run["macro_classifiers"] for run in runs])]),
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
are the problems' best possible values.""",
)
