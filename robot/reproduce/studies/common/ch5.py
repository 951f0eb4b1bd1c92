"""Thesis Tables 5.3 and 5.4 on the simulated cans: learning without and with transfer, the
runs the ``ch5-baseline`` and ``ch5-transfer`` studies measure.

``baseline_run`` runs Algorithm 4 on every can under one seed (Table 5.3: ĝ and ĥ of every
part × action, the functional pair; N without transfer). ``transfer_run`` presents the cans in
order, each learned with Algorithm 6 from the ones before (Table 5.4), next to Algorithm 4 on
the same can and seed: N without and with transfer, the source, the functional pair found.
Both measure what the code does; nothing is copied from the thesis.
"""

from __future__ import annotations

import functools
from collections import Counter
from collections.abc import Sequence
from typing import Literal

from pydantic import field_validator

from robot.reproduce.framework import SeedResult, StudyConfig

THESIS_CANS = ("o1", "o2", "o3", "o4", "o5")
NEW_CANS = ("slide", "pedal")
Perception = Literal["truth", "camera"]

class PartLearningConfig(StudyConfig):
    """Which cans, in which order, seen how."""

    cans: tuple[str, ...] = THESIS_CANS
    """The cans, in the order they are presented (a can name or a can file, .yaml)."""
    perceptions: tuple[Perception, ...] = ("truth", "camera")
    """How the cans are seen: the simulator's ground truth and/or the rendered head camera
    (OpenCV), each a separate run of every can."""

    @field_validator("cans", "perceptions")
    @classmethod
    def _not_empty(cls, values: tuple) -> tuple:
        if not values or len(set(values)) != len(values):
            raise ValueError("give at least one, each once")
        return values

    @field_validator("cans")
    @classmethod
    def _known(cls, cans: tuple[str, ...]) -> tuple[str, ...]:
        from sim.canfile import CanFileError, find_can

        for can in cans:
            try:
                find_can(can)
            except CanFileError as error:
                raise ValueError(str(error)) from None
        return cans

class PairModel(SeedResult):
    """A (part, action) pair's ĝ (5.16) and ĥ (5.17): intercept and slope, and its samples."""

    part: str
    action: str
    n: int
    g: tuple[float, float]
    h: tuple[float, float]

class Found(SeedResult):
    """The functional pair a learner found, its θ and the opening it reached (None if none)."""

    part: str | None
    action: str | None
    theta: float | None
    opening: float | None

class BaselineRow(Found):
    """Algorithm 4 on one can: N, the pair found, every pair's models."""

    n: int
    models: list[PairModel]

class TransferRow(Found):
    """Algorithm 6 on one can from the cans before it, beside Algorithm 4 on the same can."""

    n_with: int
    n_without: int
    source: str | None
    branch: str | None
    first_try: str | None

def _learn(learner, world, can: str, seed: int, perception: str):
    """Fit ``learner`` on ``can`` freshly reset under ``seed``."""
    from behaviours.part_learning import CanUnderTest
    from behaviours.perception import make_perception
    from sim.canfile import find_can

    world.reset(find_can(can), seed=seed)
    target = CanUnderTest(world, make_perception(perception))
    learner.fit(target)
    target.restore()
    return learner

def _found(learner) -> dict[str, object]:
    found = learner.functional_
    if found is None:
        return {"part": None, "action": None, "theta": None, "opening": None}
    reached = next(t for t in learner.trials_
                   if (t.part, t.action, t.theta) == (found.part, found.action, found.theta)
                   and t.reached)
    return {"part": found.part, "action": found.action, "theta": round(found.theta, 4),
            "opening": round(reached.state_after, 4)}

def _models(learner) -> list[PairModel]:
    return [PairModel(part=part, action=action, n=model.n_samples_,
                      g=(round(model.g_intercept_, 4), round(model.g_slope_, 4)),
                      h=(round(model.h_intercept_, 4), round(model.h_slope_, 4)))
            for (part, action), model in learner.models_.items()]

def baseline_run(seed: int, cans: Sequence[str], perception: str) -> dict[str, BaselineRow]:
    """Algorithm 4 on every can under one seed."""
    from behaviours.learners.baseline import PartBasedLearner
    from sim.world import GarbageWorld

    world = GarbageWorld("o1", seed=0)
    try:
        rows = {}
        for can in cans:
            learner = _learn(PartBasedLearner(random_state=seed), world, can, seed, perception)
            rows[can] = BaselineRow(n=learner.n_actions_, **_found(learner),
                                    models=_models(learner))
        return rows
    finally:
        world.close()

def transfer_run(seed: int, cans: Sequence[str], perception: str) -> dict[str, TransferRow]:
    """Table 5.4 under one seed: each can learned with transfer from the ones before it (in
    order, from an empty database) and, for N without transfer, with Algorithm 4."""
    from behaviours.learners.baseline import PartBasedLearner
    from behaviours.learners.known_objects import KnownObject
    from behaviours.learners.transfer import TransferLearner
    from sim.world import GarbageWorld

    world = GarbageWorld("o1", seed=0)
    known: list[KnownObject] = []
    try:
        rows = {}
        for can in cans:
            learner = _learn(TransferLearner(database=list(known), random_state=seed), world,
                             can, seed, perception)
            known.append(KnownObject.learned(can, learner))
            first = learner.trials_[0] if learner.trials_ else None
            baseline = _learn(PartBasedLearner(random_state=seed), world, can, seed, perception)
            rows[can] = TransferRow(
                n_with=learner.n_actions_, n_without=baseline.n_actions_,
                source=learner.source_, branch=learner.branch_, **_found(learner),
                first_try=None if first is None else f"{first.action}({first.part})")
        return rows
    finally:
        world.close()

@functools.cache
def true_pair(can: str) -> tuple[str, str]:
    """The can's functional (part, action), as its can file declares it."""
    from sim.canfile import find_can

    return find_can(can).functional


def found_pair(row: Found, can: str) -> float:
    """1 when the run found the can's functional pair, else 0."""
    return float((row.part, row.action) == true_pair(can))

def most_frequent(values: Sequence[object]) -> object:
    """The most frequent value (ties: the first seen)."""
    return Counter(values).most_common(1)[0][0]
