"""How XCS chooses an action (thesis App. A): the prediction array of eq. 3.8 over the match
set, then greedily by eq. 3.9 when it exploits, at random among the permitted actions when
it explores, or, with consistent actions, keeping the previous action while its action set
[A]-1 still matches."""

from __future__ import annotations

import numpy as np

from .xcs_population import FITNESS, PREDICTION, Population

_all = np.logical_and.reduce
"""The ufunc reduction itself: ndarray.all adds a Python-level call per use."""


def prediction_array(population: Population, match: np.ndarray, actions: np.ndarray,
                     n: int) -> np.ndarray:
    """Eq. 3.8: fitness-weighted mean prediction per action of the match set ``match``
    (``actions``: its classifiers' actions, ``n`` the number of actions), NaN where none
    advocates (fitness is always > 0, so a zero weight means no advocate)."""
    stats = population.stats.take(match, axis=1)
    fitness = stats[FITNESS]
    weights = np.bincount(actions, weights=fitness, minlength=n)
    weighted = np.bincount(actions, weights=fitness * stats[PREDICTION], minlength=n)
    if _all(weights):
        return weighted / weights
    return np.divide(weighted, weights, out=np.full(n, np.nan), where=weights > 0)


def best_action(values: list[float], permitted: np.ndarray, rng: np.random.Generator) -> int:
    """Eq. 3.9 over the permitted actions (``values``: their predictions), ties broken at
    random."""
    best = max(values)
    ties = [index for index, value in enumerate(values) if value == best]
    index = ties[0] if len(ties) == 1 else ties[int(rng.random() * len(ties))]
    return int(permitted[index])


def explore_action(permitted: np.ndarray, rng: np.random.Generator, population: Population,
                   words: np.ndarray, previous_rows: np.ndarray | None,
                   previous_action: int) -> int:
    """A random permitted action (all are advocated after covering); given the previous
    step's action set (consistent actions, App. A), its action is kept with probability equal
    to the share (by numerosity) of that set that still matches the state ``words``: always
    when all of it matches, never when none does."""
    if previous_rows is not None and previous_action in permitted:
        rows = previous_rows[population.alive(previous_rows)]
        numerosity = population.numerosity[rows]
        if rows.size:
            share = numerosity[population.matches(rows, words)].sum() / numerosity.sum()
            if share >= 1.0 or rng.random() < share:
                return previous_action
    return permitted.item(int(rng.random() * permitted.size))
