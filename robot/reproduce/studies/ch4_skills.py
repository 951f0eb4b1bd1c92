"""``ch4-skills``: goal generation and paired skills with the 8 learned forward models (thesis
§4.5, Table 4.1): the first and last action of every opening and closing sequence, e_o^g and
e_o."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Annotated, Literal

import numpy as np
from pydantic import Field

from robot.reproduce.framework import (
    Claim,
    Figure,
    Metric,
    Panel,
    Progress,
    Reading,
    SeedResult,
    Series,
    Study,
    in_turn,
)
from robot.reproduce.studies.common.ch4 import (
    CH4_DEVIATIONS,
    CONFIGURATIONS,
    METHODS,
    SETUPS,
    Configuration,
    ExplorationConfig,
    explore,
)

FORWARD_MODELS = [(f"FM{i + 1}", SETUPS[name].part, method, SETUPS[name].dims, name)
                  for i, (name, method) in enumerate(
                      (n, m) for n in ("lid-1d", "lid-3d", "handle-1d", "handle-3d")
                      for m in ("random", "active"))]
"""Table 4.1's numbering: FM1 lid random 1-D, FM2 lid active 1-D, ..., FM8 handle active 3-D."""
OPENING_SIGN = {"lid": 1.0, "handle": -1.0}
"""Table 4.1: the push-lid opens by extending the arm (Δx > 0), the pull-handle by pulling."""
PHASES = ("open", "close")
THESIS_FIRST = {  # (fm, phase) -> (e_o^g, e_o) of the sequence's first action, Table 4.1
    ("FM1", "open"): (0.018, 0.009), ("FM1", "close"): (-0.031, -0.009),
    ("FM2", "open"): (0.033, 0.025), ("FM2", "close"): (-0.019, -0.002),
    ("FM3", "open"): (0.034, 0.016), ("FM3", "close"): (-0.012, -0.021),
    ("FM4", "open"): (0.031, 0.019), ("FM4", "close"): (-0.044, -0.035),
    ("FM5", "open"): (0.008, 0.007), ("FM5", "close"): (-0.019, -0.017),
    ("FM6", "open"): (0.017, 0.011), ("FM6", "close"): (-0.006, -0.044),
    ("FM7", "open"): (0.017, 0.007), ("FM7", "close"): (-0.019, -0.038),
    ("FM8", "open"): (0.009, 0.012), ("FM8", "close"): (-0.003, 0.001),
}
TRAININGS = ("algorithm3", "full_budget")
"""Which forward model generates the goals: F as Algorithm 3 returns it (stopped where (4.10)
held, else after N_s), or F after all N_s steps (what the thesis's random runs, which never
met (4.10), had)."""


class Config(ExplorationConfig):
    """Algorithm 3's parameters and the skill acquisition's (§4.5)."""

    tau: Annotated[float, Field(gt=0.0)] = 0.01
    """τ of eq. 4.15, the thesis's 0.01. The ``close`` camera sees effects of 0.01–0.04 a step
    while the part moves and below 0.005 once it is fully open or closed, so τ tells the two
    apart as in Table 4.1."""
    max_steps: Annotated[int, Field(ge=1)] = 50
    """A sequence also ends after this many actions (the thesis's ended on (4.15) after 1–6)."""
    grid_points: Annotated[int, Field(ge=2), Reading(
        "§4.5: A_M \"is a selected set of M actions, e.g., evenly sampled in A\" (no M "
        "given); Table 4.1's Δx are 0.008 whenever the arm extends and −0.010 whenever it "
        "contracts, as a 10-point grid without its upper end gives, while its Δy, Δz reach "
        "+0.010.")] = 11
    """Points of the even grid A_M per action dimension (M = 11 or 11³ in 3-D; eqs 4.12,
    4.16)."""
    grid_upper: Annotated[Literal["included", "excluded"], Reading(
        "§4.5 and Table 4.1 (see `grid_points`): Δx never reaches +0.010 in Table 4.1.")] = (
        "included")
    """Whether A_M's grid ends at the upper bound (+0.01 m) or one step short of it
    (`excluded` with 10 points: −0.010, −0.008, ..., 0.008 m per dimension)."""


class SkillRow(SeedResult):
    """One opening or closing sequence: its first and last action, goal and effect."""

    fm: str
    part: str
    policy: str
    dims: int
    training: str
    exploration_steps: int
    phase: str
    first_state: float
    first_action: list[float]
    goal: float
    effect: float
    last_state: float
    last_action: list[float]
    last_goal: float
    last_effect: float
    steps: int
    terminated: bool
    states: list[float]


class Result(SeedResult):
    perception: str
    sequences: list[SkillRow]


def _action3(action: tuple[float, ...]) -> list[float]:
    """An action as [Δx, Δy, Δz] (1-D actions move along x only)."""
    return [round(float(v), 4) for v in (list(action) + [0.0, 0.0])[:3]]


def run(config: Config, seed: int, progress: Progress) -> Result:
    """Learn each forward model with Algorithm 3 or random exploration, then, from a closed
    can, maximise then minimise the predicted effect (4.12–4.18) with each training's F."""
    sequences = []
    for fm, part, method, dims, name in in_turn(FORWARD_MODELS, progress):
        explorer, contact = explore(SETUPS[name], method, seed, config, stop=False)
        contact.world.close()
        stopped_at = explorer.history_.converged_at or explorer.n_steps_
        for training, model in zip(TRAININGS, (explorer.stopped_model_,
                                               explorer.forward_model_), strict=True):
            info = {"fm": fm, "part": part, "policy": method, "dims": dims,
                    "training": training,
                    "exploration_steps": stopped_at if training == "algorithm3"
                    else explorer.n_steps_}
            sequences += [SkillRow(**info, **row)
                          for row in _skills(model, SETUPS[name], seed, config)]
    return Result(perception=config.perception, sequences=sequences)


def _skills(model, setup: Configuration, seed: int, config: Config) -> list[dict]:
    """The opening and the closing sequence that ``model`` generates on a closed can."""
    from behaviours.contact import CONTACT_CAMERA, PartContact
    from behaviours.learners.skill_acquisition import acquire_skills
    from behaviours.perception import make_perception
    from sim.world import GarbageWorld

    world = GarbageWorld(setup.can, seed=seed)
    try:
        with PartContact(world, setup.part, dims=setup.dims,
                         perception=make_perception(config.perception, CONTACT_CAMERA)) as held:
            found = acquire_skills(model, held, n_grid=config.grid_points, tau=config.tau,
                                   max_steps=config.max_steps,
                                   endpoint=config.grid_upper == "included")
    finally:
        world.close()
    rows = []
    for phase, sequence in zip(PHASES, found, strict=True):
        first, last = sequence.steps[0], sequence.steps[-1]
        rows.append({
            "phase": phase,
            "first_state": round(first.state, 4), "first_action": _action3(first.action),
            "goal": round(first.goal, 4), "effect": round(first.effect, 4),
            "last_state": round(last.state, 4), "last_action": _action3(last.action),
            "last_goal": round(last.goal, 4), "last_effect": round(last.effect, 4),
            "steps": len(sequence.steps), "terminated": sequence.terminated,
            "states": [round(step.state + step.effect, 5) for step in sequence.steps],
        })
    return rows


def expected_sign(row: SkillRow) -> bool:
    """Whether the first action's Δx has Table 4.1's sign for this part and phase."""
    sign = OPENING_SIGN[row.part] * (1.0 if row.phase == "open" else -1.0)
    return row.first_action[0] * sign > 0


def _row(seed: Result, fm: str, phase: str, training: str) -> SkillRow | None:
    return next((row for row in seed.sequences if row.fm == fm and row.phase == phase
                 and row.training == training), None)


def _sign(seed: Result, fm: str, phase: str, training: str) -> float | None:
    row = _row(seed, fm, phase, training)
    return None if row is None else float(expected_sign(row))


def signs_share(seed: Result, training: str) -> float | None:
    """The share of the seed's sequences (every forward model and phase) whose first Δx has
    Table 4.1's sign."""
    rows = [row for row in seed.sequences if row.training == training]
    return sum(map(expected_sign, rows)) / len(rows) if rows else None


def metrics(config: Config) -> list[Metric[Result]]:
    """Per forward model and phase: seeds with Table 4.1's sign of Δx (for both trainings),
    and the first action's goal e_o^g and effect e_o (Algorithm 3's F) beside the thesis's
    (our `close` camera sees the opening about as large as its NAO camera did); per
    training, the share of all sequences with the thesis's sign."""
    rows: list[Metric[Result]] = []
    for fm, part, method, dims, _ in FORWARD_MODELS:
        for phase in PHASES:
            label, key = f"{fm} ({part}, {method}, {dims}-D) {phase}", f"{fm}.{phase}"
            for training in TRAININGS:
                rows.append(Metric(
                    f"{key}.{training}.sign", f"{label}: first Δx has Table 4.1's sign "
                    f"({training})", lambda s, a=(fm, phase, training): _sign(s, *a), 1.0,
                    "Table 4.1"))
            goal, effect = THESIS_FIRST[(fm, phase)]
            first = (fm, phase, "algorithm3")
            rows += [
                Metric(f"{key}.goal", f"{label}: first e_o^g",
                       lambda s, a=first: getattr(_row(s, *a), "goal", None), goal,
                       "Table 4.1"),
                Metric(f"{key}.effect", f"{label}: first e_o",
                       lambda s, a=first: getattr(_row(s, *a), "effect", None), effect,
                       "Table 4.1"),
            ]
    for training in TRAININGS:
        rows.append(Metric(f"{training}.sign_share", f"all sequences: share whose first Δx "
                           f"has Table 4.1's sign ({training})",
                           lambda s, t=training: signs_share(s, t), 1.0, "Table 4.1"))
    return rows


def claims(config: Config) -> list[Claim]:
    return [Claim(f"The learned forward models generate skills that open and close the parts "
                  f"as Table 4.1's do: the first Δx has the thesis's sign more often than a "
                  f"coin would ({training} models)", f"{training}.sign_share", 0.5)
            for training in TRAININGS]


def figures(config: Config, seeds: Sequence[Result]) -> list[Figure]:
    """s_o after each action of the opening and closing sequences, per configuration."""
    out = []
    for name in CONFIGURATIONS:
        setup, panels = SETUPS[name], []
        for phase in PHASES:
            series = []
            for method in METHODS:
                runs = [row.states for seed in seeds for row in seed.sequences
                        if row.phase == phase and row.policy == method
                        and row.training == "algorithm3" and setup.part == row.part
                        and setup.dims == row.dims]
                length = max(len(run) for run in runs)
                padded = [run + [np.nan] * (length - len(run)) for run in runs]
                series.append(Series(f"FM from {method} exploration",
                                     list(range(1, length + 1)), padded))
            panels.append(Panel(f"{phase}: action", "s_o after the action", series))
        out.append(Figure(f"skills-{name}", f"{name}: acquired skills from a closed can",
                          panels))
    return out


STUDY = Study(
    name="ch4-skills",
    description="Goal generation and paired open/close skills from 8 forward models (Table 4.1)",
    config=Config, result=Result, run=run, metrics=metrics, claims=claims, figures=figures,
    quick={"scale": 0.05}, default_seeds=10, deviations=CH4_DEVIATIONS,
    headline=("algorithm3.sign_share", "full_budget.sign_share"),
    notes="""\
Each seed learns the 8 forward models of Table 4.1 with Algorithm 3 or the random baseline
(the setup of `ch4-exploration`), and generates skills twice: with F as Algorithm 3 returns it
(`training: algorithm3`, stopped where (4.10) first held, else at N_s) and with F after all
N_s steps (`full_budget`, as the thesis's random runs, which never met (4.10), had). Holding
the part of a closed can, the robot generates goals with the model: A_M is an even grid of
`grid_points` values per action dimension (11: M = 11 or 11³ = 1331), e_o^g the largest (then
smallest) predicted effect (4.12, 4.16), a* its action (4.13, 4.17); a sequence ends when
|e_o| < τ (4.15) or after `max_steps` actions. The JSON lists the first and last action of
each sequence with the first action's goal and effect; "Table 4.1's sign" is that of the
first Δx (push-lid: open by extending, close by contracting; pull-handle the other way
round). s_o is seen by the `close` camera (a fully opened can fills about 0.12–0.13 of its
image, as the thesis's NAO camera saw it); the hand's reach ends a few centimetres from where
it took hold, so a part is fully opened or closed within about six steps (see
`ch4-exploration`'s notes).
""",
)
