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
    Deviation,
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
    NavigationConfig,
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


class Config(NavigationConfig):
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
                                            trials // 2, config, config.n_step,
                                            {"start": config.start})
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
    last_before = half - 1 if half % 2 == 0 else half - 2  # the last exploit trial before
    for method in METHODS:
        get = _run("truth", method)
        rows += [
            Metric(f"truth.{method}.shortfall_before", f"{method}: exploit trial "
                   f"{last_before + 1}'s payoff short of the best its start allows",
                   lambda s, get=get: shortfall(get(s), last_before, half), 0.0,
                   "§3.5.8: both methods solved it from the 4th trial"),
            Metric(f"truth.{method}.shortfall_last", f"{method}: exploit trial {trials}'s "
                   "payoff short of the best its start allows",
                   lambda s, get=get: shortfall(get(s), trials - 1, half),
                   0.0 if method == "affordance_xcs" else None,
                   "§3.5.8: after the exchange affordance-based XCS found the way"),
        ]
    rows += [
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


def shortfall(run: TaskRun, trial: int, exchange: int) -> float:
    """The best payoff trial ``trial`` (0-based) could earn from its start lane, less what it
    earned (0: optimal). Runs without recorded starts began in the right-most lane."""
    from behaviours.xcs_tasks import NavigationTask
    from sim.navigation import START_LANE

    lane = START_LANE if run.starts is None else run.starts[trial]
    return NavigationTask.best_payoff(lane, trial >= exchange) - run.payoff[trial]


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
        Claim("Before the exchange, affordance-based XCS's last exploit trial earns the best "
              "payoff its start allows (§3.5.8: solved from the 4th trial)",
              "truth.affordance_xcs.shortfall_before", 0.0, "same"),
        Claim("Before the exchange, standard XCS's last exploit trial earns the best payoff "
              "its start allows (§3.5.8: both solved it from the 4th trial)",
              "truth.standard_xcs.shortfall_before", 0.0, "same"),
        Claim(f"Affordance-based XCS's last exploit trial {after} comes nearer the best payoff "
              "its start allows than standard XCS's (§3.5.8)",
              "truth.affordance_xcs.shortfall_last", "truth.standard_xcs.shortfall_last",
              "less"),
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
    deviations=(
        Deviation("Robot", "a NAO walking on the table (§3.4, §3.5.1).", "a block on one "
                  "round foot moved by force-limited slides in steps of d_walk = 0.15 m, so "
                  "it stands in one of four lanes; walking stops on touching a box (its "
                  "sonar, §3.5.3), pushing does not."),
        Deviation("Object codes", "the movable box is \"1000\" (a white marker), the fixed "
                  "one \"1111\", \"1100\" or \"1011\" as seen (Table 3.3).",
                  "colour bits are the marker's RGB channels: blue \"1001\" moves, red "
                  "\"1100\" does not."),
        Deviation("Runs", "5 experiments on the NAO, averaged (§3.5.8).",
                  "10 seeds per perception mode, each with its own paired test."),
    ),
    notes="""\
**Setup** (`sim/navigation.py`, `behaviours/xcs_tasks.py`): a 0.75 x 0.6 m table; each trial
starts in one of four lanes 0.15 m apart (`start`, below). Two 27 cm wide boxes
block every lane: a 0.4 kg one with a blue marker that slides when pushed and a 40 kg one with
a red marker that the robot's 20 N cannot move. Actions 000/001/011/010 walk 0.15 m left,
ahead, right or push ahead; walking is stopped by a box; a step past the table's side edge
drops the robot (the trial ends). Destination: a line 0.4 m ahead; eq. 3.14 with d_dst =
d_move = 0.05 m (a sideways step is punished: it brings the robot no nearer). State: eq. 3.12,
o = (height bit by eq. 3.11, RGB bits of the marker colour), 4 location bits (row and lateral
bin of the marker); the red box is "1100", the blue "1001" (the thesis's white box was
"1000"). XCS: Table 7.1 (N = 100, P# = 0.6, θGA = 5, ...); n_step = 10; whether exploit
trials update XCS and where the filter applies are parameters (below); every push updates
the affordance table in both kinds of trial. Camera mode: markers found by HSV
segmentation, placed by their known width (depth) and the robot's known pose.

**Reading**: success rate and steps are over all trials 11-20 (explore and exploit); the
thesis's Figs. 3.5-3.6 show the same averages per trial. A trial's best payoff depends on its
start lane: 1000 facing the movable box, 100 less per step sideways to a lane that does
(§3.5.8's start facing the unmovable box after the exchange: 800).""",
)
