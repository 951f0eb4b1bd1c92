"""``appA-search``: thesis Appendix A's head-camera search: steps to find the target before and
after it moves, and a Table 7.2-style listing of the learned rules.

Each seed runs XCS (Table 7.1, consistent-action exploration) for 20 trials with the target
up-left of the head, then 20 with it on the right; odd trials explore, even trials exploit.
The thesis does not say how many trials it ran.
"""

from __future__ import annotations

from collections.abc import Sequence
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
    Reading,
    Reference,
    SeedResult,
    Series,
    Study,
    in_turn,
    markdown_table,
)
from robot.reproduce.studies.common.tasks import (
    MODES,
    TaskRun,
    TrialConfig,
    even_trials,
    experienced_rules,
    experiment,
    identical,
    opened_world,
    per_trial,
    window,
)

PLACES = ("up_left", "right")
FEWEST = {"up_left": 4, "right": 3}
"""App. A: 2 looks left and 2 up find the target up-left; 3 looks right find it on the right."""
BEFORE_AFTER = {"up_left": "before", "right": "after"}


class Config(TrialConfig):
    """App. A's search with Table 7.1's XCS."""

    trials_per_place: Annotated[int, Field(ge=2)] = 20
    """Trials with the target at each place (scaled to an even number, at least 2)."""
    step_limit: Annotated[int, Field(ge=1)] = 20
    """Table 7.1's N_s: looks per trial at most."""
    consistent_actions: Annotated[bool, Reading(
        "App. A, Explore Trials: \"consistent actions are adopted ... If the new input still "
        "matches all the classifiers in [A], then it continues with the current action\"; "
        "its footnote 3: \"A variety of exploration strategies were also tested\".")] = True
    """App. A's exploration: keep the action while [A]-1 still matches (true), or a random
    advocated action at every explore step (false, Wilson's XCS)."""
    last_exploit: Annotated[int, Field(ge=1)] = 3
    """The steps of the last this-many exploit trials at each place measure what was learned."""
    rules_listed: Annotated[int, Field(ge=1)] = 5
    """Rules in the Table 7.2-style listing."""

    def per_place(self) -> int:
        return even_trials(self.trials_per_place, self.scale, 2)


class Result(SeedResult):
    per_place: int
    truth: TaskRun
    camera: TaskRun


def run(config: Config, seed: int, progress: Progress) -> Result:
    per_place = config.per_place()
    runs = {}
    with opened_world("search") as world:
        for mode in in_turn(MODES, progress):
            runs[mode] = experiment(world, "search", mode, "standard_xcs", seed,
                                    2 * per_place, per_place, config, config.step_limit,
                                    consistent_actions=config.consistent_actions)
    return Result(per_place=per_place, **runs)


def _trials(per_place: int, place: str) -> tuple[int, int]:
    return (0, per_place) if place == "up_left" else (per_place, 2 * per_place)


def last_exploits(run: TaskRun, start: int, stop: int, count: int) -> float:
    """Mean steps of the last ``count`` exploit trials in trials start..stop-1."""
    exploits = [t for t in range(start, stop) if not run.explore[t]][-count:]
    return sum(run.steps[t] for t in exploits) / len(exploits)


def best_exploit(run: TaskRun, start: int, stop: int) -> int | None:
    """Fewest steps of an exploit trial that found the target in trials start..stop-1."""
    return min((run.steps[t] for t in range(start, stop)
                if not run.explore[t] and run.success[t]), default=None)


def metrics(config: Config) -> list[Metric[Result]]:
    per_place = config.per_place()
    rows: list[Metric[Result]] = []
    for mode, place in product(MODES, PLACES):
        start, stop = _trials(per_place, place)
        label, when = f"{'camera: ' if mode == 'camera' else ''}", BEFORE_AFTER[place]

        def get(seed: Result, mode: str = mode) -> TaskRun:
            return getattr(seed, mode)

        rows += [
            Metric(f"{mode}.{place}.matches_thesis", f"{label}seeds whose fewest looks "
                   f"{when} it moves equal the thesis's run ({FEWEST[place]})",
                   lambda s, get=get, a=start, b=stop, place=place: float(
                       best_exploit(get(s), a, b) == FEWEST[place]), 1.0,
                   "App. A's single run: 4 looks up-left, then 3 right"),
            Metric(f"{mode}.{place}.last_exploit_steps", f"{label}steps to find it {when} it "
                   f"moves ({place}), last {config.last_exploit} exploit trials",
                   lambda s, get=get, a=start, b=stop: last_exploits(get(s), a, b,
                                                                     config.last_exploit),
                   float(FEWEST[place]), "App. A: the fewest looks that find it"),
            Metric(f"{mode}.{place}.best_exploit_steps", f"{label}fewest looks in an exploit "
                   f"trial that found it {when} it moves ({place})",
                   lambda s, get=get, a=start, b=stop: best_exploit(get(s), a, b),
                   float(FEWEST[place]), "App. A: 4 looks up-left, then 3 right"),
            Metric(f"{mode}.{place}.exploit_found", f"{label}exploit trials that find it "
                   f"({place})", lambda s, get=get, a=start, b=stop: window(
                       get(s), get(s).success, a, b, exploit_only=True), 1.0,
                   "App. A (the robot learned to find it)"),
        ]
    rows.append(Metric("camera_identical", "camera runs identical to truth runs, trial by "
                       "trial", lambda s: identical({"run": s.truth}, {"run": s.camera}), 1.0,
                       "camera perception agrees with truth (issue 9)"))
    return rows


def claims(config: Config) -> list[Claim]:
    """App. A reports one run: the fewest looks an exploit trial took at each place (compared
    like for like with each seed's fewest), and what the learned policy does at the end."""
    out = []
    for place in PLACES:
        when = BEFORE_AFTER[place]
        out += [
            Claim(f"A run finds the target {when} it moves in the fewest looks, "
                  f"{FEWEST[place]}, as App. A's single run did: more often than not",
                  f"truth.{place}.matches_thesis", 0.5, "greater"),
            Claim(f"The robot learned to find the target {when} it moves in the fewest "
                  f"looks, {FEWEST[place]}: the last exploit trials take that many (App. A)",
                  f"truth.{place}.last_exploit_steps", float(FEWEST[place]), "same"),
        ]
    return out


def figures(config: Config, seeds: Sequence[Result]) -> list[Figure]:
    per_place = seeds[0].per_place
    x = list(range(1, 2 * per_place + 1))
    return [Figure("steps", "Head-camera search: steps to find the target (App. A)", [
        Panel("trial (odd: explore, even: exploit)",
              f"steps (N_s = {config.step_limit}: not found)",
              [Series(mode, x, per_trial([getattr(s, mode) for s in seeds], "steps"))
               for mode in MODES],
              [Reference(4.0, "fewest, up-left"), Reference(3.0, "fewest, right"),
               Reference(per_place + 0.5, "target moves", vertical=True)]),
    ])]


def listings(config: Config, seeds: Sequence[Result]) -> str:
    """Markdown: a Table 7.2-style listing of the first seed's most experienced rules."""
    rules = experienced_rules(seeds[0].truth.rules, config.rules_listed)
    return "\n".join([
        "## XCS rules of the first seed, truth (Table 7.2 style: the "
        f"{config.rules_listed} most experienced)", "",
        markdown_table(["ID", "condition", "action", "prediction", "error", "fitness", "size",
                        "exp.", "num."], rules)])


STUDY = Study(
    name="appA-search",
    description="Thesis App. A: a head camera learns with XCS to find a target, before and "
                "after the target moves; Table 7.2-style rules",
    config=Config, result=Result, run=run, metrics=metrics, claims=claims, figures=figures,
    listings=listings, quick={"scale": 0.2}, default_seeds=10,
    headline=("truth.up_left.matches_thesis", "truth.right.matches_thesis",
              "truth.up_left.last_exploit_steps", "truth.up_left.exploit_found"),
    deviations=(
        Deviation("Trials", "not given; one run, its rules listed (Table 7.2).",
                  "20 trials with the target up-left, then 20 with it on the right, "
                  "alternating explore and exploit; every seed is a run like the thesis's."),
        Deviation("Target", "an object on the table, first up-left, then on the right "
                  "(Fig. 7.2); 2 looks left and 2 up, then 3 looks right found it.",
                  "a red 5 cm cube placed so that exactly those looks bring it into the "
                  "centre ninth."),
    ),
    notes="""\
**Setup** (`sim/search.py`, `behaviours/blob_grid.py`): a pan-tilt head with the NAO's limits
(yaw ±2.079, pitch -0.67..0.51 rad) and camera field of view (47.6 x 36.8°), 0.1 rad per
action (00 up, 01 right, 10 down, 11 left), reset to rest past the movement boundary ±0.5 rad;
a red 5 cm cube 1 m away, up-left (yaw 0.32, pitch -0.285) and then right (yaw -0.42), placed
so that exactly 2 looks left and 2 up, or 3 right, bring it into the centre ninth. State: the
9-bit blob grid; reward 1000 when the fifth bit is 1; N_s = 20; XCS with Table 7.1 and App.
A's consistent actions in explore trials (keep the action while [A]-1 still matches).

**Reading**: before the move, early exploit trials often find the target (in 4 looks at best),
but once the rules are general the whole previous action set keeps matching, so consistent
exploration repeats one action to the step limit, the target is no longer reached, and the
predictions wash out; the last exploit trials then fail. After the move three identical looks
suffice, which that same exploration finds at once.""",
)
