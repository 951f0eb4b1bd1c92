"""``xcs-woods2``: XCS as Wilson's animat in Woods2 (Wilson 1995).

The optimum is 1.7 steps to food on average (1.6875 exactly over the map's 288 blank cells);
Wilson's XCS comes down to about 2 steps within 4,000 problems.
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
from robot.reproduce.lcs_experiments import first_at_or_below, woods_experiment
from robot.reproduce.lcs_problems import WOODS2, WOODS2_CODES

WILSON_WOODS2 = {
    "N": 800, "beta": 0.2, "gamma": 0.71, "alpha": 0.1, "epsilon_0": 10.0, "nu": 5.0,
    "theta_ga": 25, "chi": 0.8, "mu": 0.01, "theta_del": 20, "delta": 0.1, "theta_sub": 20,
    "p_hash": 0.5, "prediction_init": 10.0, "error_init": 0.0, "fitness_init": 0.01,
    "ga_subsumption": True, "action_set_subsumption": False,
}
"""Wilson's Woods2 settings (1995), with B&W's power-law accuracy (nu = 5) and GA
subsumption."""

EXPLORE_PROBLEMS = 4_000
STEP_LIMIT = 50
"""A problem not at food after this many steps ends (as in xcslib and XCSJava)."""
WILSON_OPTIMUM = 1.7
WILSON_STEPS = 2.0


def run_seed(seed: int, scale: float, progress: Progress) -> dict:
    return woods_experiment(WOODS2, WOODS2_CODES, max(100, round(EXPLORE_PROBLEMS * scale)),
                            WILSON_WOODS2, seed, progress, STEP_LIMIT)


def woods_summary(seeds: list[dict]) -> dict:
    """Final steps to food, when the curve first reaches 2 steps, and the population size."""
    steps, steps_sd = mean_and_std([seed["final_steps"] for seed in seeds])
    reached = [first_at_or_below(seed["problems"], seed["steps"], WILSON_STEPS)
               for seed in seeds]
    to_two, to_two_sd = mean_and_std(reached)
    macro, macro_sd = mean_and_std([seed["final_macro_classifiers"] for seed in seeds])
    return {
        "final_steps": steps, "final_steps_sd": steps_sd, "optimum": seeds[0]["optimum"],
        "explore_problems": seeds[0]["problems"][-1] if seeds[0]["problems"] else 0,
        "problems_to_2_steps": to_two if None not in reached else None,
        "problems_to_2_steps_sd": to_two_sd if None not in reached else None,
        "seeds_reaching_2_steps": sum(value is not None for value in reached),
        "seeds": len(seeds),
        "final_macro_classifiers": macro, "final_macro_classifiers_sd": macro_sd,
    }


def compare(summary: dict, seeds: list[dict]) -> list[Comparison]:
    return [
        Comparison("steps to food, last 50 exploit problems, at the end",
                   summary["final_steps"], summary["final_steps_sd"], WILSON_STEPS,
                   "Wilson 1995: about 2 within 4,000 problems"),
        Comparison("the same against the optimum", summary["final_steps"],
                   summary["final_steps_sd"], summary["optimum"],
                   "shortest paths over the map (Wilson: 1.7)"),
        Comparison(f"explore problems until 2 steps or fewer "
                   f"({summary['seeds_reaching_2_steps']}/{summary['seeds']} seeds got there)",
                   summary["problems_to_2_steps"], summary["problems_to_2_steps_sd"]),
        Comparison("macro-classifiers at the end", summary["final_macro_classifiers"],
                   summary["final_macro_classifiers_sd"]),
    ]


def woods_figure(runs: dict[str, list[dict]], stem: str, title: str,
                 ylim: tuple[float, float] | None = (0.0, 8.0)) -> Figure:
    """Steps to food and population size, one series per labelled set of seeds; the first
    problems' long walks are cut off at 8 steps unless ``ylim`` says otherwise."""
    first = next(iter(runs.values()))
    x, optimum = first[0]["problems"], first[0]["optimum"]
    return Figure(stem, title, [
        Panel("explore problems", "steps to food (last 50 exploit problems)",
              [Series(label, x, [seed["steps"] for seed in seeds])
               for label, seeds in runs.items()],
              [Reference(WILSON_STEPS, "Wilson 1995: about 2 within 4,000"),
               Reference(optimum, f"optimum {optimum:.2f}")], ylim=ylim),
        Panel("explore problems", "population size (macro-classifiers)",
              [Series(label, x, [seed["macro_classifiers"] for seed in seeds])
               for label, seeds in runs.items()]),
    ])


def figures(seeds: list[dict]) -> list[Figure]:
    return [woods_figure({"goalagent XCS": seeds}, "steps", "XCS in Woods2 (N = 800)")]


REPRODUCTION = Reproduction(
    name="xcs-woods2",
    description="XCS as Wilson's animat in Woods2 (Wilson 1995): steps to food against "
                "explore problems",
    run_seed=run_seed, summarize=woods_summary, compare=compare, figures=figures,
    notes=f"""\
**Setup** (Wilson 1995): Woods2 is the 30 × 15 toroidal map distributed with Lanzi's xcslib,
rocks O and Q, food F and G; the animat senses its 8 neighbours clockwise from north, 3 bits
each (blank 000, O 010, Q 011, F 110, G 111: 24 bits), and moves into one of them (a rock
blocks the move). A problem starts on a random blank cell and ends on food (reward 1000) or
after {STEP_LIMIT} steps. Explore and exploit problems alternate; the curve is the mean steps
to food over the last 50 exploit problems. Parameters: N = 800, β = 0.2, γ = 0.71, α = 0.1,
ε0 = 10, ν = 5, θGA = 25, χ = 0.8, μ = 0.01, θdel = 20, δ = 0.1, θsub = 20, P# = 0.5,
p_I = 10, ε_I = 0, F_I = 0.01, GA subsumption on. Wilson's 1995 accuracy was exponential
(κ = exp(ln α (ε − ε0)/ε0)); this is the power law of Butz & Wilson and the thesis (eq. 7.6).""",
)
