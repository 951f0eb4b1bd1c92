"""``ch3-stacking``: Table 3.3's stacking rows, the payoff curve and the object the learned
policy chooses (thesis §3.5, Fig. 3.4).

Each seed runs affordance-based XCS (Algorithm 2) for 20 alternating explore / exploit trials
in the stacking world, in truth and in camera perception. The thesis gives no trial count for
this task; 20 is the navigation task's.
"""

from __future__ import annotations

from collections import Counter

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
from robot.reproduce.task_runs import (
    MODES,
    even_trials,
    experiment,
    identical_runs,
    majority_movability,
    opened_world,
    per_trial,
    seeds_with,
    window_mean,
)

TRIALS = 20
BOX, FOAM = "1001", "0010"
STAND, SQUAT = "100", "101"
THESIS_ROWS = {(FOAM, STAND): ("0000 100 0", 5), (FOAM, SQUAT): ("0000 101 1", 6),
               (BOX, STAND): ("1000 100 1", 7)}
"""Our codes for Table 3.3's rows 5-7: the low foam (thesis 0000) pushed standing is unmoved,
squatting moved; the high box (thesis 1000) pushed standing moved."""
CHOICES = {"choose_box": "box", "choose_foam": "foam"}


def run_seed(seed: int, scale: float, progress: Progress) -> dict:
    trials = even_trials(TRIALS, scale, 4)
    result: dict = {"trials": trials}
    with opened_world("stacking") as world:
        for index, mode in enumerate(MODES):
            result[mode] = experiment(world, "stacking", mode, "affordance_xcs", seed, trials,
                                      trials)
            progress((index + 1) / len(MODES))
    return result


def chosen_object(run: dict) -> str | None:
    """What the learned policy asks for first: the first choice of the last exploit trial."""
    last = max(t for t, explore in enumerate(run["explore"]) if not explore)
    return CHOICES.get(run["first_action"][last])


def _mode_summary(runs: list[dict], trials: int) -> dict:
    choices = Counter(chosen_object(run) or "none" for run in runs)
    payoff, payoff_sd = window_mean(runs, "payoff", trials // 2, trials, exploit_only=True)
    return {
        "movability": majority_movability([run["movability"] for run in runs]),
        "chosen_object": choices.most_common(1)[0][0],
        "chosen_counts": dict(choices),
        "exploit_payoff_second_half": payoff, "exploit_payoff_second_half_sd": payoff_sd,
        "success_rate": window_mean(runs, "success", 0, trials)[0],
    }


def summarize(seeds: list[dict]) -> dict:
    trials = seeds[0]["trials"]
    summary = {"trials": trials, "seeds": len(seeds)}
    summary.update(_mode_summary([s["truth"] for s in seeds], trials))
    summary["camera"] = _mode_summary([s["camera"] for s in seeds], trials)
    summary["camera_identical_to_truth"] = identical_runs([(s["truth"], s["camera"])
                                                           for s in seeds])
    return summary


def compare(summary: dict, seeds: list[dict]) -> list[Comparison]:
    rows = []
    for mode in MODES:
        tables = [s[mode]["movability"] for s in seeds]
        for (obj, action), (thesis, number) in THESIS_ROWS.items():
            effect = int(thesis[-1])
            rows.append(Comparison(
                f"{mode}: seeds whose table says {obj}/{action} -> {effect}",
                seeds_with(tables, [obj, action, effect]), None, 1.0,
                f"Table 3.3 row {number} ({thesis})"))
        chosen = [chosen_object(s[mode]) == "box" for s in seeds]
        rows.append(Comparison(f"{mode}: seeds whose learned policy chooses the high box",
                               sum(chosen) / len(chosen), None, 1.0,
                               "§3.5.8: it learned to choose the high box"))
        last = [s[mode]["payoff"][-1] for s in seeds]
        rows.append(Comparison(f"{mode}: exploit payoff in the last trial",
                               *mean_and_std(last), 900.0,
                               "choose the box (-100), push it once (+1000): eq. 3.15"))
    rows.append(Comparison("camera runs identical to truth runs, trial by trial",
                           summary["camera_identical_to_truth"], None, 1.0,
                           "camera perception agrees with truth (issue 9)"))
    return rows


def figures(seeds: list[dict]) -> list[Figure]:
    trials = seeds[0]["trials"]
    x = list(range(1, trials + 1))
    return [Figure("payoff", "Payoff in the stacking task, affordance-based XCS", [
        Panel("trial (odd: explore, even: exploit)", "payoff (eq. 3.16)",
              [Series(mode, x, per_trial([s[mode] for s in seeds], "payoff"))
               for mode in MODES],
              [Reference(900.0, "box: choose + push"),
               Reference(700.0, "foams: 3 x (choose + push)")]),
    ])]


def listings(summary: dict, seeds: list[dict]) -> str:
    """Markdown: Table 3.3's stacking rows beside ours, and the chosen objects."""
    rows = []
    for obj, action, effect in summary["movability"]:
        thesis = THESIS_ROWS.get((obj, action))
        rows.append([obj, action, effect,
                     "—" if thesis is None else f"{thesis[0]} (row {thesis[1]})"])
    lines = ["## Learned movability (Table 3.3, stacking rows)", "",
             markdown_table(["object", "action", "effect (most seeds)", "thesis"], rows)]
    lines += ["", f"Chosen object (first choice of the last exploit trial), truth: "
              f"{summary['chosen_counts']}; camera: {summary['camera']['chosen_counts']}."]
    return "\n".join(lines)


REPRODUCTION = Reproduction(
    name="ch3-stacking",
    description="Thesis Table 3.3 (stacking rows) and §3.5.8: pose-dependent movability of a "
                "high box and a low foam, and the object the learned policy chooses",
    run_seed=run_seed, summarize=summarize, compare=compare, figures=figures, listings=listings,
    quick_scale=0.2, default_seeds=10,
    notes="""\
**Setup** (`sim/stacking.py`): a table 36 cm high; the robot stands near its edge; a high box
(36 cm, blue marker, code 1001) and low foams (12 cm, green, code 0010), all 20 x 20 cm.
Actions 100/101 push the object in front 0.34 m ahead standing (the bar sweeps 14-20 cm above
the table, over the foam) or squatting (3-9 cm); 110/111 ask the operator for the box or a
foam. Pushed off the edge, an object slides onto a lift beside the table that sinks until the
stack's top is level with the table (objects pushed over a bare edge tip over or jam, which
makes no stack); the goal is a stack as high as the table: the box alone or three foams.
Reward eq. 3.15; n_step = 10; XCS as Table 7.1; affordance-based XCS (Algorithm 2).""",
)
