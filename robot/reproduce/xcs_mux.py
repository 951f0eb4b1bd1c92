"""``xcs-mux``: XCS on the 6- and 11-multiplexer as Wilson (1995) ran it.

Wilson reports 100% performance on the 6-multiplexer after about 5,000 problems with N = 400,
and on the 11-multiplexer after about 15,000 with N = 800.
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
from robot.reproduce.lcs_experiments import multiplexer_experiment

WILSON_MULTIPLEXER = {
    "beta": 0.2, "alpha": 0.1, "epsilon_0": 10.0, "nu": 5.0, "theta_ga": 25, "chi": 0.8,
    "mu": 0.04, "theta_del": 20, "delta": 0.1, "theta_sub": 20, "p_hash": 0.33,
    "prediction_init": 10.0, "error_init": 0.0, "fitness_init": 0.01, "gamma": 0.0,
    "ga_subsumption": True, "action_set_subsumption": False,
}
"""Wilson's multiplexer settings (1995), with B&W's power-law accuracy (nu = 5) and GA
subsumption; gamma plays no part in single-step problems."""

PROBLEMS = {"mux6": (2, 400, 10_000), "mux11": (3, 800, 30_000)}
"""Per problem: address bits, population size N, explore problems in a full run."""
WILSON_PROBLEMS_TO_100 = {"mux6": 5_000, "mux11": 15_000}
LABELS = {"mux6": "6-multiplexer", "mux11": "11-multiplexer"}


def explore_problems(name: str, scale: float) -> int:
    return max(100, round(PROBLEMS[name][2] * scale))


def run_seed(seed: int, scale: float, progress: Progress) -> dict:
    """Both multiplexers, one after the other, for one seed."""
    sizes = {name: explore_problems(name, scale) for name in PROBLEMS}
    total, done, result = sum(sizes.values()), 0, {}
    for name, (address_bits, population_size, _) in PROBLEMS.items():
        offset = done
        result[name] = multiplexer_experiment(
            address_bits, sizes[name], {**WILSON_MULTIPLEXER, "N": population_size}, seed,
            lambda fraction, offset=offset, size=sizes[name]: progress(
                (offset + fraction * size) / total))
        done += sizes[name]
    return result


def summarize(seeds: list[dict]) -> dict:
    """Per multiplexer: final accuracy and explore problems to 100% (mean, sd over seeds)."""
    summary = {}
    for name in PROBLEMS:
        runs = [seed[name] for seed in seeds]
        accuracy, accuracy_sd = mean_and_std([run["final_accuracy"] for run in runs])
        reached = [run["problems_to_99"] for run in runs if run["problems_to_99"] is not None]
        problems, problems_sd = mean_and_std(reached)
        first, first_sd = mean_and_std([run["first_at_99"] for run in runs])
        macro, macro_sd = mean_and_std([run["final_macro_classifiers"] for run in runs])
        summary[name] = {
            "final_accuracy": accuracy, "final_accuracy_sd": accuracy_sd,
            "problems_to_99": problems if len(reached) == len(runs) else None,
            "problems_to_99_sd": problems_sd if len(reached) == len(runs) else None,
            "seeds_reaching_99": len(reached), "seeds": len(runs),
            "first_at_99": first, "first_at_99_sd": first_sd,
            "explore_problems": runs[0]["problems"][-1] if runs[0]["problems"] else 0,
            "final_macro_classifiers": macro, "final_macro_classifiers_sd": macro_sd,
        }
    return summary


def compare(summary: dict, seeds: list[dict]) -> list[Comparison]:
    rows = []
    for name in PROBLEMS:
        part, label = summary[name], LABELS[name]
        rows += [
            Comparison(f"{label}: fraction correct, last 50 exploit problems",
                       part["final_accuracy"], part["final_accuracy_sd"], 1.0,
                       "Wilson 1995: 100%"),
            Comparison(f"{label}: explore problems until 50/50 correct for good "
                       f"({part['seeds_reaching_99']}/{part['seeds']} seeds got there)",
                       part["problems_to_99"], part["problems_to_99_sd"],
                       WILSON_PROBLEMS_TO_100[name],
                       f"Wilson 1995: about {WILSON_PROBLEMS_TO_100[name]:,}, "
                       f"N = {PROBLEMS[name][1]}"),
            Comparison(f"{label}: macro-classifiers at the end", part["final_macro_classifiers"],
                       part["final_macro_classifiers_sd"]),
        ]
    return rows


def figures(seeds: list[dict]) -> list[Figure]:
    """Both multiplexers on one figure: fraction correct, and population size."""
    accuracy, population, references = [], [], [Reference(1.0, "100% (Wilson 1995)")]
    for name in PROBLEMS:
        runs = [seed[name] for seed in seeds]
        label = f"{LABELS[name]}, N = {PROBLEMS[name][1]}"
        accuracy.append(Series(label, runs[0]["problems"], [run["accuracy"] for run in runs]))
        population.append(Series(label, runs[0]["problems"],
                                 [run["macro_classifiers"] for run in runs]))
        references.append(Reference(WILSON_PROBLEMS_TO_100[name],
                                    f"Wilson 1995: {LABELS[name]} at 100% by about "
                                    f"{WILSON_PROBLEMS_TO_100[name]:,}", vertical=True))
    return [Figure("curves", "XCS on the 6- and 11-multiplexer", [
        Panel("explore problems", "fraction correct (last 50 exploit problems)", accuracy,
              references, ylim=(0.4, 1.02)),
        Panel("explore problems", "population size (macro-classifiers)", population),
    ])]


REPRODUCTION = Reproduction(
    name="xcs-mux",
    description="XCS on the 6- and 11-multiplexer (Wilson 1995): fraction correct and "
                "population size against explore problems",
    run_seed=run_seed, summarize=summarize, compare=compare, figures=figures,
    notes="""\
**Setup** (Wilson 1995, with Butz & Wilson's 2001 algorithm): explore and exploit problems
alternate; each problem is a uniformly random input; reward 1000 for the right output, 0
otherwise; an exploit problem acts greedily and learns nothing. Performance is the fraction of
the last 50 exploit problems answered correctly, plotted against explore problems.
Parameters: N = 400 (6-mux) and 800 (11-mux), β = 0.2, α = 0.1, ε0 = 10, ν = 5, θGA = 25,
χ = 0.8, μ = 0.04, θdel = 20, δ = 0.1, θsub = 20, P# = 0.33, p_I = 10, ε_I = 0, F_I = 0.01,
GA subsumption on, action-set subsumption off. "Until 50/50 correct for good" is the explore
problem from which the fraction over the last 50 exploit problems stayed at 0.99 or more (all
50 right) to the end of the run; `first_at_99` in the JSON is the first time it got there.""",
)
