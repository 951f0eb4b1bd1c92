"""Wilson's experimental protocol for XCS on the multiplexer and in woods (Wilson 1995).

Explore and exploit problems alternate. An explore problem learns (random actions among
those advocated); an exploit problem acts greedily and learns nothing, and is what the curves
measure: the fraction correct, or the steps to food, over the last 50 exploit problems,
plotted against the number of explore problems, with the population size in
macro-classifiers beside it.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable

import numpy as np

from behaviours.learners.xcs import XCS
from robot.reproduce.lcs_problems import Woods

WINDOW = 50
"""Exploit problems in the moving performance measure (Wilson 1995)."""
RECORD_EVERY = 50
"""Explore problems between two points of a curve."""
REWARD = 1000.0


def environment_rng(seed: int) -> np.random.Generator:
    """The problems' random stream, independent of the learner's (both from ``seed``)."""
    return np.random.default_rng([seed, 0x5EED])


def multiplexer_experiment(address_bits: int, explore_problems: int, params: dict, seed: int,
                           progress: Callable[[float], None]) -> dict:
    """XCS on the (address_bits + 2**address_bits)-bit multiplexer, reward 1000 when right.

    ``problems_to_99``: the explore problem from which the fraction correct over the last 50
    exploit problems stayed at 0.99 or more (all 50 right) to the end of the run;
    ``first_at_99``: the first time it got there."""
    length = address_bits + 2 ** address_bits
    rng = environment_rng(seed)
    xcs = XCS(2, random_state=seed, **params)
    window: deque[bool] = deque(maxlen=WINDOW)
    curve: dict[str, list] = {"problems": [], "accuracy": [], "macro_classifiers": []}
    first_perfect = stays_perfect = None
    for problem in range(1, explore_problems + 1):
        for explore in (True, False):
            state = format(int(rng.integers(2 ** length)), f"0{length}b")
            answer = int(state[address_bits + int(state[:address_bits], 2)])
            action = xcs.act(state, explore=explore)
            xcs.reward(REWARD if action == answer else 0.0, done=True)
        window.append(action == answer)
        accuracy = sum(window) / len(window)
        if len(window) == WINDOW and accuracy >= 0.99:
            first_perfect = first_perfect or problem
            stays_perfect = stays_perfect or problem
        else:
            stays_perfect = None
        if problem % RECORD_EVERY == 0:
            curve["problems"].append(problem)
            curve["accuracy"].append(accuracy)
            curve["macro_classifiers"].append(xcs.macro_count)
            progress(problem / explore_problems)
    return {**curve, "final_accuracy": sum(window) / len(window),
            "problems_to_99": stays_perfect, "first_at_99": first_perfect,
            "final_macro_classifiers": xcs.macro_count}


def woods_experiment(rows: tuple[str, ...], codes: dict[str, str], explore_problems: int,
                     params: dict, seed: int, progress: Callable[[float], None],
                     step_limit: int) -> dict:
    """XCS as Wilson's animat in a woods map: each problem starts on a random blank cell and
    ends at food (reward 1000) or after ``step_limit`` steps."""
    world = Woods(rows, codes, environment_rng(seed))
    xcs = XCS(8, random_state=seed, **params)
    window: deque[int] = deque(maxlen=WINDOW)
    curve: dict[str, list] = {"problems": [], "steps": [], "macro_classifiers": []}
    for problem in range(1, explore_problems + 1):
        _trial(xcs, world, explore=True, step_limit=step_limit)
        window.append(_trial(xcs, world, explore=False, step_limit=step_limit))
        if problem % RECORD_EVERY == 0:
            curve["problems"].append(problem)
            curve["steps"].append(sum(window) / len(window))
            curve["macro_classifiers"].append(xcs.macro_count)
            progress(problem / explore_problems)
    return {**curve, "final_steps": sum(window) / len(window),
            "final_macro_classifiers": xcs.macro_count, "optimum": world.optimal_steps()}


def _trial(xcs: XCS, world: Woods, explore: bool, step_limit: int) -> int:
    """One problem; returns its number of steps."""
    state = world.reset()
    for step in range(1, step_limit + 1):
        state, reward, done = world.step(xcs.act(state, explore=explore))
        xcs.reward(reward, done)
        if done:
            return step
    xcs.end_trial()
    return step_limit


def first_at_or_below(problems: list[int], values: list[float], level: float) -> int | None:
    """The first recorded problem count whose value is at or below ``level``."""
    return next((p for p, v in zip(problems, values, strict=True) if v <= level), None)
