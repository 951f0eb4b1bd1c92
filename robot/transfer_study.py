"""Thesis Tables 5.3 and 5.4 on the simulated cans: learning without and with transfer.

``baseline_seed`` runs Algorithm 4 on every can and seed (Table 5.3: ĝ and ĥ of every part ×
action, the functional pair; N without transfer). ``transfer_seed`` presents the cans in
order, each learned with Algorithm 6 from the ones before (Table 5.4), next to Algorithm 4 on
the same can and seed: N without and with transfer, the source, the functional pair found.
Both measure what the code does; nothing is copied from the thesis. The results are plain
dicts (JSON-ready), run per seed by ``goalagent reproduce ch5-baseline|ch5-transfer``
(``robot/reproduce/ch5_baseline.py``, ``ch5_transfer.py``).
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Callable, Sequence
from statistics import mean

from behaviours.learners.baseline import PartBasedLearner
from behaviours.learners.known_objects import KnownObject
from behaviours.learners.transfer import TransferLearner
from behaviours.part_learning import CanUnderTest
from behaviours.perception import make_perception
from sim.canfile import find_can
from sim.world import GarbageWorld

THESIS_CANS = ("o1", "o2", "o3", "o4", "o5")
NEW_CANS = ("slide", "pedal")
Progress = Callable[[str], None]


def _run(learner: PartBasedLearner, world: GarbageWorld, can: str, seed: int,
         perception: str) -> PartBasedLearner:
    """Fit ``learner`` on ``can`` freshly reset under ``seed``."""
    world.reset(find_can(can), seed=seed)
    target = CanUnderTest(world, make_perception(perception))
    learner.fit(target)
    target.restore()
    return learner


def _found(learner: PartBasedLearner) -> dict[str, object]:
    """The functional pair a learner found, its θ and the opening it reached (None if none)."""
    found = learner.functional_
    if found is None:
        return {"part": None, "action": None, "theta": None, "opening": None}
    reached = next(t for t in learner.trials_
                   if (t.part, t.action, t.theta) == (found.part, found.action, found.theta)
                   and t.reached)
    return {"part": found.part, "action": found.action, "theta": round(found.theta, 4),
            "opening": round(reached.state_after, 4)}


def _models(learner: PartBasedLearner) -> list[dict[str, object]]:
    """Every pair's ĝ (5.16) and ĥ (5.17) coefficients and sample count."""
    return [{"part": part, "action": action, "n": model.n_samples_,
             "g": [round(model.g_intercept_, 4), round(model.g_slope_, 4)],
             "h": [round(model.h_intercept_, 4), round(model.h_slope_, 4)]}
            for (part, action), model in learner.models_.items()]


def baseline_seed(seed: int, cans: Sequence[str] = THESIS_CANS, perception: str = "truth",
                  progress: Progress = lambda line: None) -> dict[str, dict]:
    """Algorithm 4 on every can under one seed: N, the pair found, every pair's models."""
    world = GarbageWorld("o1", seed=0)
    row: dict[str, dict] = {}
    try:
        for can in cans:
            learner = _run(PartBasedLearner(random_state=seed), world, can, seed, perception)
            row[can] = {"n": learner.n_actions_, **_found(learner), "models": _models(learner)}
            progress(f"ch5-baseline {perception} seed {seed} {can}: N = "
                     f"{learner.n_actions_}, pair {row[can]['part']}/{row[can]['action']}")
    finally:
        world.close()
    return row


def baseline_summary(rows: Sequence[dict[str, dict]]) -> dict[str, dict]:
    """Per can over the seeds' rows: mean N without transfer, the most frequent pair, and on
    how many seeds it was the can's true functional pair."""
    summary = {}
    for can in rows[0]:
        runs = [row[can] for row in rows]
        summary[can] = {"n_without": mean(r["n"] for r in runs),
                        **_most_frequent(runs, ("part", "action")),
                        "found": sum((r["part"], r["action"]) == find_can(can).functional
                                     for r in runs)}
    return summary


def _most_frequent(runs: Sequence[dict], keys: Sequence[str]) -> dict[str, object]:
    """The most frequent value of each key over the runs (ties: the first seen)."""
    return {key: Counter(r[key] for r in runs).most_common(1)[0][0] for key in keys}


def transfer_seed(seed: int, cans: Sequence[str] = THESIS_CANS, perception: str = "truth",
                  progress: Progress = lambda line: None) -> dict[str, dict]:
    """Table 5.4 under one seed: each can learned with transfer from the ones before it (in
    order, from an empty database) and, for N without transfer, with Algorithm 4."""
    world = GarbageWorld("o1", seed=0)
    known: list[KnownObject] = []
    row: dict[str, dict] = {}
    try:
        for can in cans:
            started = time.perf_counter()
            learner = _run(TransferLearner(database=list(known), random_state=seed), world, can,
                           seed, perception)
            known.append(KnownObject.learned(can, learner))
            first = learner.trials_[0] if learner.trials_ else None
            entry = {"n_with": learner.n_actions_, "source": learner.source_,
                     "branch": learner.branch_, **_found(learner),
                     "first_try": None if first is None else f"{first.action}({first.part})",
                     "seconds_with": round(time.perf_counter() - started, 2)}
            baseline = _run(PartBasedLearner(random_state=seed), world, can, seed, perception)
            entry["n_without"] = baseline.n_actions_
            row[can] = entry
            progress(f"ch5-transfer {perception} seed {seed} {can}: N_tran = "
                     f"{entry['n_with']} (without {entry['n_without']}), source "
                     f"{entry['source']}, {entry['branch']}, pair "
                     f"{entry['part']}/{entry['action']}")
    finally:
        world.close()
    return row


def transfer_summary(rows: Sequence[dict[str, dict]]) -> dict[str, dict]:
    """Per can over the seeds' rows: mean N without and with transfer, the most frequent
    source, part, action and branch, how many seeds found the true functional pair, and
    whether transfer never took more actions than Algorithm 4."""
    summary = {}
    for can in rows[0]:
        runs = [row[can] for row in rows]
        summary[can] = {
            "n_without": mean(r["n_without"] for r in runs),
            "n_with": mean(r["n_with"] for r in runs),
            **_most_frequent(runs, ("source", "part", "action", "branch")),
            "found": sum((r["part"], r["action"]) == find_can(can).functional for r in runs),
            "never_worse": all(r["n_with"] <= r["n_without"] for r in runs),
        }
    return summary
