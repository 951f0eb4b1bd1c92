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
from robot.reproduce.lcs_problems import MAZE4, MAZE_CODES
from robot.reproduce.xcs_woods2 import STEP_LIMIT, WILSON_WOODS2

RUNS = {
    "generalising": ("XCS, P# = 0.5", {**WILSON_WOODS2, "N": 1600}),
    "generalising_p033": ("XCS, P# = 0.33", {**WILSON_WOODS2, "N": 1600, "p_hash": 0.33}),
    "specific": ("XCS without # (P# = 0, μ = 0)",
                 {**WILSON_WOODS2, "N": 1600, "p_hash": 0.0, "mu": 0.0}),
}
"""Wilson's woods settings with Lanzi's population size for his mazes (N = 1600)."""
EXPLORE_PROBLEMS = 4_000
NEAR_OPTIMAL = 4.0
"""Within half a step of the optimum (3.5): "reached the optimum" in the table."""


def run_seed(seed: int, scale: float, progress: Progress) -> dict:
    problems = max(100, round(EXPLORE_PROBLEMS * scale))
    result = {}
    for index, (run, (_, params)) in enumerate(RUNS.items()):

        def report(fraction: float, index: int = index) -> None:
            progress((index + fraction) / len(RUNS))

        result[run] = woods_experiment(MAZE4, MAZE_CODES, problems, params, seed, report,
                                       STEP_LIMIT)
    return result


def _summary(runs: list[dict]) -> dict:
    steps, steps_sd = mean_and_std([run["final_steps"] for run in runs])
    reached = [first_at_or_below(run["problems"], run["steps"], NEAR_OPTIMAL) for run in runs]
    first, first_sd = mean_and_std(reached)
    macro, macro_sd = mean_and_std([run["final_macro_classifiers"] for run in runs])
    return {
        "final_steps": steps, "final_steps_sd": steps_sd, "optimum": runs[0]["optimum"],
        "seeds_near_optimal_at_end": sum(run["final_steps"] <= NEAR_OPTIMAL for run in runs),
        "seeds_ever_near_optimal": sum(value is not None for value in reached),
        "problems_to_near_optimal": first, "problems_to_near_optimal_sd": first_sd,
        "seeds": len(runs),
        "final_macro_classifiers": macro, "final_macro_classifiers_sd": macro_sd,
    }


def summarize(seeds: list[dict]) -> dict:
    return {run: _summary([seed[run] for seed in seeds]) for run in RUNS}


def compare(summary: dict, seeds: list[dict]) -> list[Comparison]:
    sources = {
        "generalising": "optimum; Lanzi: XCS often not optimal here",
        "generalising_p033": "optimum",
        "specific": "optimum; Lanzi: reached without #s",
    }
    rows = []
    for run, (label, _) in RUNS.items():
        part = summary[run]
        rows += [
            Comparison(f"{label}: steps to food, last 50 exploit problems, at the end "
                       f"({part['seeds_near_optimal_at_end']}/{part['seeds']} seeds at "
                       f"{NEAR_OPTIMAL:g} or fewer)", part["final_steps"],
                       part["final_steps_sd"], part["optimum"], sources[run]),
            Comparison(f"{label}: explore problems until {NEAR_OPTIMAL:g} steps or fewer "
                       f"first ({part['seeds_ever_near_optimal']}/{part['seeds']} seeds got "
                       "there)", part["problems_to_near_optimal"],
                       part["problems_to_near_optimal_sd"]),
            Comparison(f"{label}: macro-classifiers at the end",
                       part["final_macro_classifiers"], part["final_macro_classifiers_sd"]),
        ]
    return rows


def figures(seeds: list[dict]) -> list[Figure]:
    first = seeds[0]["generalising"]
    x, optimum = first["problems"], first["optimum"]
    runs = {label: [seed[run] for seed in seeds] for run, (label, _) in RUNS.items()}
    return [Figure("steps", "XCS in Maze4 (N = 1600)", [
        Panel("explore problems", "steps to food (last 50 exploit problems)",
              [Series(label, x, [r["steps"] for r in rs]) for label, rs in runs.items()],
              [Reference(optimum, f"optimum {optimum:.1f}")], ylim=(0.0, STEP_LIMIT + 1)),
        Panel("explore problems", "population size (macro-classifiers)",
              [Series(label, x, [r["macro_classifiers"] for r in rs])
               for label, rs in runs.items()]),
    ])]


REPRODUCTION = Reproduction(
    name="xcs-maze4",
    description="XCS in Lanzi's Maze4 with and without generalisation (Lanzi 1997, 1999): "
                "steps to food against explore problems",
    run_seed=run_seed, summarize=summarize, compare=compare, figures=figures,
    quick_scale=0.025,
    notes=f"""\
**Setup**: Maze4 as in Lanzi (1997) and xcsf's `maze4.txt`: 8 × 8, walls all round, one food
cell; the animat senses its 8 neighbours clockwise from north, 2 bits each (blank 00,
obstacle 10, food 11: 16 bits), moves into one of them (an obstacle blocks the move). The
optimum is 3.5 steps (BFS over the 26 blank cells). Protocol and parameters as `xcs-woods2`
(explore and exploit problems alternate, {STEP_LIMIT}-step limit, reward 1000 at food; β = 0.2,
γ = 0.71, α = 0.1, ε0 = 10, ν = 5, θGA = 25, χ = 0.8, μ = 0.01, θdel = 20, δ = 0.1,
θsub = 20, GA subsumption on) with N = 1600 and {EXPLORE_PROBLEMS:,} explore problems; exploit
problems learn nothing (thesis App. A: learning only in explore mode).

**What the literature says**: Lanzi (1997, "A study of the generalization capabilities of
XCS"; 1999, "An analysis of generalization in the XCS classifier system") found that in mazes
where few generalisations are possible (Maze4, Maze5, Maze6) XCS's generalisation can keep it
from the optimal policy — overgeneral classifiers that are rarely contradicted — and that
often it does not reach a stable solution; XCS without don't-care symbols reaches the optimum
easily; his Specify operator (not part of this XCS) repairs the generalising one. No
per-problem number is quoted here from those papers: the reference is the optimum.""",
)
