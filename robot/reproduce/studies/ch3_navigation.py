"""``ch3-navigation``: thesis Figs. 3.5 and 3.6, Table 3.2 and Table 3.3's navigation rows.

Each seed runs the 20-trial navigation experiment of §3.5.7 four times: affordance-based XCS
(Algorithm 2) and standard XCS, each in truth and in camera perception. Odd trials explore,
even trials exploit; the boxes are exchanged after trial 10.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from itertools import product
from typing import Annotated

from pydantic import Field

from robot.reproduce.framework import (
    Claim,
    Figure,
    Metric,
    Panel,
    Progress,
    Reference,
    SeedResult,
    Series,
    Study,
    in_turn,
    markdown_table,
)
from robot.reproduce.studies.common.tasks import (
    MODES,
    TaskConfig,
    TaskRun,
    experienced_rules,
    experiment,
    identical,
    knows,
    majority_movability,
    opened_world,
    per_trial,
    window,
)

METHODS = ("affordance_xcs", "standard_xcs")
MOVABLE, FIXED, PUSH = "1001", "1100", "010"
"""Our codes: the blue-marked movable box (thesis "1000"), the red-marked fixed one (thesis
"1111", "1100", "1011" as seen whole or in part), action 010 (push d_walk ahead)."""


class Config(TaskConfig):
    """§3.5.7's navigation experiment with Table 7.1's XCS."""

    rules_listed: Annotated[int, Field(ge=1)] = 21
    """Rules in the Table 3.2-style listing (Table 3.2 lists 21)."""


class Methods(SeedResult):
    affordance_xcs: TaskRun
    standard_xcs: TaskRun


class Result(SeedResult):
    trials: int
    truth: Methods
    camera: Methods


def run(config: Config, seed: int, progress: Progress) -> Result:
    trials = config.scaled_trials()
    runs: dict[str, dict[str, TaskRun]] = {mode: {} for mode in MODES}
    with opened_world("navigation") as world:
        for mode, method in in_turn(product(MODES, METHODS), progress):
            runs[mode][method] = experiment(world, "navigation", mode, method, seed, trials,
                                            trials // 2, config, config.n_step)
    return Result(trials=trials, **{mode: Methods(**runs[mode]) for mode in MODES})


def _run(mode: str, method: str) -> Callable[[Result], TaskRun]:
    return lambda seed: getattr(getattr(seed, mode), method)


def metrics(config: Config) -> list[Metric[Result]]:
    trials = config.scaled_trials()
    half = trials // 2
    after = f"trials {half + 1}-{trials}"
    rows: list[Metric[Result]] = []
    for mode, method in product(MODES, METHODS):
        get, key, label = _run(mode, method), f"{mode}.{method}", (
            f"{'camera: ' if mode == 'camera' else ''}{method}")
        reference, source = ((0.0, "§3.5.8: standard XCS failed within 10 trials")
                             if method == "standard_xcs" else
                             (None, "§3.5.8: it succeeded (Figs. 3.5-3.6, no rate given)"))
        rows += [
            Metric(f"{key}.success_after", f"{label}: success rate, {after}",
                   lambda s, get=get: window(get(s), get(s).success, half, trials),
                   reference, source),
            Metric(f"{key}.exploit_success_after", f"{label}: exploit success rate, {after}",
                   lambda s, get=get: window(get(s), get(s).success, half, trials, True)),
            Metric(f"{key}.steps_after", f"{label}: steps per trial, {after}",
                   lambda s, get=get: window(get(s), get(s).steps, half, trials),
                   None, "Fig. 3.6 (curve only)"),
        ]
    truth = _run("truth", "affordance_xcs")
    last_before = half - 1 if half % 2 == 0 else half - 2  # the last exploit trial before
    rows += [
        Metric("truth.affordance_xcs.payoff_before_exchange",
               f"affordance_xcs: exploit payoff in trial {last_before + 1}",
               lambda s: truth(s).payoff[last_before], 1000.0,
               "§3.5.8: both solve it from the 4th trial; three pushes earn 1000"),
        Metric("truth.affordance_xcs.payoff_last", f"affordance_xcs: exploit payoff in trial "
               f"{trials}", lambda s: truth(s).payoff[trials - 1], 800.0,
               "§3.5.8: after the exchange, 2 steps left (-200) then 3 pushes (+1000)"),
        Metric("camera_identical", "camera runs identical to truth runs, trial by trial",
               lambda s: identical(dict(s.truth), dict(s.camera)), 1.0,
               "camera perception agrees with truth (issue 9)"),
        Metric("knows_movable", f"seeds whose tables (both methods, truth) say "
               f"{MOVABLE}/{PUSH} moved", lambda s: _both_know(s, (MOVABLE, PUSH, 1)), 1.0,
               "Table 3.3 row 3 (1000 010 1)"),
        Metric("knows_fixed", f"seeds whose tables (both methods, truth) say {FIXED}/{PUSH} "
               "unmoved", lambda s: _both_know(s, (FIXED, PUSH, 0)), 1.0,
               "Table 3.3 rows 1, 2, 4 (1100, 1111, 1011 010 0)"),
    ]
    return rows


def _both_know(seed: Result, row: tuple[str, str, int]) -> float:
    return min(knows(getattr(seed.truth, method), row) for method in METHODS)


def claims(config: Config) -> list[Claim]:
    after = "after the boxes are exchanged"
    return [
        Claim(f"Affordance-based XCS succeeds more often than standard XCS {after} (§3.5.8, "
              "Fig. 3.5)", "truth.affordance_xcs.success_after",
              "truth.standard_xcs.success_after"),
        Claim(f"Affordance-based XCS succeeds more often in exploit trials {after} (§3.5.8)",
              "truth.affordance_xcs.exploit_success_after",
              "truth.standard_xcs.exploit_success_after"),
        Claim(f"Affordance-based XCS needs fewer steps per trial {after} (Fig. 3.6)",
              "truth.affordance_xcs.steps_after", "truth.standard_xcs.steps_after", "less"),
        Claim(f"Standard XCS fails {after} (§3.5.8: it failed within 10 trials)",
              "truth.standard_xcs.success_after", 0.0, "same"),
    ]


def figures(config: Config, seeds: Sequence[Result]) -> list[Figure]:
    trials = seeds[0].trials
    x = list(range(1, trials + 1))
    exchange = Reference(trials / 2 + 0.5, "boxes exchanged", vertical=True)
    result = []
    for stem, key, title, ylabel, references in (
            ("fig3_5", "payoff", "Average payoff in the navigation task (thesis Fig. 3.5)",
             "payoff (eq. 3.16)", [Reference(1000.0, "maximal payoff")]),
            ("fig3_6", "steps", "Average number of steps in the navigation task (Fig. 3.6)",
             "steps", [Reference(float(config.n_step), "n_step")])):
        panels = [Panel("trial (odd: explore, even: exploit)", f"{ylabel}, {mode}",
                        [Series(method, x, per_trial([_run(mode, method)(s) for s in seeds],
                                                     key)) for method in METHODS],
                        [*references, exchange])
                  for mode in MODES]
        result.append(Figure(stem, title, panels))
    return result


def listings(config: Config, seeds: Sequence[Result]) -> str:
    """Markdown: the learned movability (Table 3.3) and a Table 3.2-style rule listing."""
    thesis = {(MOVABLE, PUSH): "1000 010 1 (row 3)",
              (FIXED, PUSH): "1100 / 1111 / 1011 010 0 (rows 1, 2, 4)"}
    movability = [[obj, action, effect, thesis.get((obj, action), "—")]
                  for obj, action, effect in majority_movability(
                      [seed.truth.affordance_xcs.movability for seed in seeds])]
    rules = experienced_rules(seeds[0].truth.affordance_xcs.rules, config.rules_listed)
    return "\n".join([
        "## Learned movability (Table 3.3, navigation rows)", "",
        markdown_table(["object", "action", "effect (most seeds)", "thesis"], movability), "",
        "## XCS rules of the first seed, affordance-based XCS, truth (Table 3.2 style: the "
        f"{config.rules_listed} most experienced)", "",
        markdown_table(["ID", "condition", "act.", "pred.", "error", "fit.", "size", "E.", "N"],
                       rules)])


STUDY = Study(
    name="ch3-navigation",
    description="Thesis Figs. 3.5-3.6, Tables 3.2-3.3: affordance-based vs standard XCS in the "
                "navigation task, boxes exchanged after 10 trials",
    config=Config, result=Result, run=run, metrics=metrics, claims=claims, figures=figures,
    listings=listings, quick={"scale": 0.2}, default_seeds=10,
    headline=("truth.affordance_xcs.success_after", "truth.standard_xcs.success_after",
              "truth.affordance_xcs.steps_after", "truth.standard_xcs.steps_after"),
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
