"""``ch3-navigation``: thesis Figs. 3.5 and 3.6, Table 3.2 and Table 3.3's navigation rows.

Each seed runs the 20-trial navigation experiment of §3.5.7 four times: affordance-based XCS
(Algorithm 2) and standard XCS, each in truth and in camera perception. Odd trials explore,
even trials exploit; the boxes are exchanged after trial 10.
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
from robot.reproduce.task_runs import (
    MODES,
    even_trials,
    experienced_rules,
    experiment,
    identical_runs,
    majority_movability,
    opened_world,
    per_trial,
    seeds_with,
    window_mean,
)

TRIALS = 20
METHODS = ("affordance_xcs", "standard_xcs")
MOVABLE, FIXED, PUSH = "1001", "1100", "010"
"""Our codes: the blue-marked movable box (thesis "1000"), the red-marked fixed one (thesis
"1111", "1100", "1011" as seen whole or in part), action 010 (push d_walk ahead)."""
RULES_LISTED = 21
"""Table 3.2 lists 21 rules."""


def run_seed(seed: int, scale: float, progress: Progress) -> dict:
    trials = even_trials(TRIALS, scale, 4)  # two before the exchange, two after
    result: dict = {"trials": trials}
    done = 0
    with opened_world("navigation") as world:
        for mode in MODES:
            result[mode] = {}
            for method in METHODS:
                result[mode][method] = experiment(world, "navigation", mode, method, seed,
                                                  trials, trials // 2)
                done += 1
                progress(done / (len(MODES) * len(METHODS)))
    return result


def _method_summary(runs: list[dict], trials: int) -> dict:
    half = trials // 2
    steps, steps_sd = window_mean(runs, "steps", half, trials)
    success, success_sd = window_mean(runs, "success", half, trials)
    exploit, exploit_sd = window_mean(runs, "success", half, trials, exploit_only=True)
    return {
        "mean_steps_11_20": steps, "mean_steps_11_20_sd": steps_sd,
        "success_rate_11_20": success, "success_rate_11_20_sd": success_sd,
        "exploit_success_rate_11_20": exploit, "exploit_success_rate_11_20_sd": exploit_sd,
        "success_rate_1_10": window_mean(runs, "success", 0, half)[0],
        "mean_payoff_11_20": window_mean(runs, "payoff", half, trials)[0],
        "movability": majority_movability([run["movability"] for run in runs]),
    }


def summarize(seeds: list[dict]) -> dict:
    trials = seeds[0]["trials"]
    summary: dict = {"trials": trials, "seeds": len(seeds)}
    for method in METHODS:
        summary[method] = _method_summary([s["truth"][method] for s in seeds], trials)
    summary["camera"] = {method: _method_summary([s["camera"][method] for s in seeds], trials)
                         for method in METHODS}
    summary["camera_identical_to_truth"] = identical_runs(
        [(s["truth"][m], s["camera"][m]) for s in seeds for m in METHODS])
    summary["rules"] = experienced_rules(seeds[0]["truth"]["affordance_xcs"]["rules"],
                                        RULES_LISTED)
    return summary


def compare(summary: dict, seeds: list[dict]) -> list[Comparison]:
    trials = summary["trials"]
    half = trials // 2
    rows = []
    for label, where in (("", summary), ("camera: ", summary["camera"])):
        for method in METHODS:
            part = where[method]
            reference, source = ((0.0, "§3.5.8: standard XCS failed within 10 trials")
                                 if method == "standard_xcs" else
                                 (None, "§3.5.8: it succeeded (Figs. 3.5-3.6, no rate given)"))
            rows.append(Comparison(f"{label}{method}: success rate, trials {half + 1}-{trials}",
                                   part["success_rate_11_20"], part["success_rate_11_20_sd"],
                                   reference, source))
            rows.append(Comparison(f"{label}{method}: exploit success rate, trials "
                                   f"{half + 1}-{trials}", part["exploit_success_rate_11_20"],
                                   part["exploit_success_rate_11_20_sd"]))
            rows.append(Comparison(f"{label}{method}: steps per trial, trials {half + 1}-{trials}",
                                   part["mean_steps_11_20"], part["mean_steps_11_20_sd"],
                                   None, "Fig. 3.6 (curve only)"))
    for key, label in (("success", "success rate"), ("steps", "steps per trial")):
        differences = [
            sum(s["truth"]["affordance_xcs"][key][half:]) / (trials - half)
            - sum(s["truth"]["standard_xcs"][key][half:]) / (trials - half) for s in seeds]
        better = sum((d > 0) if key == "success" else (d < 0) for d in differences)
        rows.append(Comparison(
            f"paired, same seed: affordance_xcs - standard_xcs {label}, trials "
            f"{half + 1}-{trials} (affordance better in {better}/{len(seeds)} seeds)",
            *mean_and_std(differences), None, "Figs. 3.5-3.6: affordance-based XCS better"))
    truth = [s["truth"]["affordance_xcs"] for s in seeds]
    last_before = max(t for t in range(half) if not truth[0]["explore"][t])
    rows.append(Comparison(
        f"affordance_xcs: exploit payoff in trial {last_before + 1}",
        *mean_and_std([run["payoff"][last_before] for run in truth]), 1000.0,
        "§3.5.8: both solve it from the 4th trial; three pushes earn 1000"))
    rows.append(Comparison(
        f"affordance_xcs: exploit payoff in trial {trials}",
        *mean_and_std([run["payoff"][trials - 1] for run in truth]), 800.0,
        "§3.5.8: after the exchange, 2 steps left (-200) then 3 pushes (+1000)"))
    rows.append(Comparison("camera runs identical to truth runs, trial by trial",
                           summary["camera_identical_to_truth"], None, 1.0,
                           "camera perception agrees with truth (issue 9)"))
    tables = [run["movability"] for method in METHODS for run in
              (s["truth"][method] for s in seeds)]
    rows.append(Comparison(f"seeds whose table says {MOVABLE}/{PUSH} moved", seeds_with(
        tables, [MOVABLE, PUSH, 1]), None, 1.0, "Table 3.3 row 3 (1000 010 1)"))
    rows.append(Comparison(f"seeds whose table says {FIXED}/{PUSH} unmoved", seeds_with(
        tables, [FIXED, PUSH, 0]), None, 1.0, "Table 3.3 rows 1, 2, 4 (1100, 1111, 1011 010 0)"))
    return rows


def figures(seeds: list[dict]) -> list[Figure]:
    trials = seeds[0]["trials"]
    x = list(range(1, trials + 1))
    exchange = Reference(trials / 2 + 0.5, "boxes exchanged", vertical=True)
    result = []
    for stem, key, title, ylabel, references in (
            ("fig3_5", "payoff", "Average payoff in the navigation task (thesis Fig. 3.5)",
             "payoff (eq. 3.16)", [Reference(1000.0, "maximal payoff")]),
            ("fig3_6", "steps", "Average number of steps in the navigation task (Fig. 3.6)",
             "steps", [Reference(10.0, "n_step")])):
        panels = [Panel("trial (odd: explore, even: exploit)", f"{ylabel}, {mode}",
                        [Series(method, x, per_trial([s[mode][method] for s in seeds], key))
                         for method in METHODS], [*references, exchange])
                  for mode in MODES]
        result.append(Figure(stem, title, panels))
    return result


def listings(summary: dict, seeds: list[dict]) -> str:
    """Markdown: the learned movability (Table 3.3) and a Table 3.2-style rule listing."""
    thesis = {(MOVABLE, PUSH): "1000 010 1 (row 3)",
              (FIXED, PUSH): "1100 / 1111 / 1011 010 0 (rows 1, 2, 4)"}
    movability = [[obj, action, effect, thesis.get((obj, action), "—")]
                  for obj, action, effect in summary["affordance_xcs"]["movability"]]
    return "\n".join([
        "## Learned movability (Table 3.3, navigation rows)", "",
        markdown_table(["object", "action", "effect (most seeds)", "thesis"], movability), "",
        "## XCS rules of seed 0, affordance-based XCS, truth (Table 3.2 style: the "
        f"{RULES_LISTED} most experienced)", "",
        markdown_table(["ID", "condition", "act.", "pred.", "error", "fit.", "size", "E.", "N"],
                       summary["rules"])])


REPRODUCTION = Reproduction(
    name="ch3-navigation",
    description="Thesis Figs. 3.5-3.6, Tables 3.2-3.3: affordance-based vs standard XCS in the "
                "navigation task, boxes exchanged after 10 trials",
    run_seed=run_seed, summarize=summarize, compare=compare, figures=figures, listings=listings,
    quick_scale=0.2, default_seeds=10,
    notes="""\
**Setup** (`sim/navigation.py`, `behaviours/xcs_tasks.py`): a 0.75 x 0.6 m table; the robot
starts in the right-most of four lanes 0.15 m apart, facing the right box. Two 27 cm wide boxes
block every lane: a 0.4 kg one with a blue marker that slides when pushed and a 40 kg one with
a red marker that the robot's 20 N cannot move. Actions 000/001/011/010 walk 0.15 m left,
ahead, right or push ahead; walking is stopped by a box; a step past the table's side edge
drops the robot (the trial ends). Destination: a line 0.4 m ahead; eq. 3.14 with d_dst =
d_move = 0.05 m (a sideways step is punished: it brings the robot no nearer). State: eq. 3.12,
o = (height bit by eq. 3.11, RGB bits of the marker colour), 4 location bits (row and lateral
bin of the marker); the red box is "1100", the blue "1001" (the thesis's white box was
"1000"). XCS: Table 7.1 (N = 100, P# = 0.6, θGA = 5, ...); n_step = 10; exploit trials do not
update XCS (App. A); every push updates the affordance table in both. The thesis averaged 5
runs on the NAO; here 10 seeds per perception mode. Camera mode: markers found by HSV
segmentation, placed by their known width (depth) and the robot's known pose.

**Reading**: success rate and steps are over all trials 11-20 (explore and exploit); the
thesis's Figs. 3.5-3.6 show the same averages per trial.""",
)
