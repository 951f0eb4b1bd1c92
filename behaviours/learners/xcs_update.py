"""UPDATE SET of XCS (Butz & Wilson 2001; thesis eq. 7.1, 7.4-7.7): the reinforcement
component's arithmetic on one action set's columns of `Population.stats`.

Two forms of the same arithmetic: `update_set` on the columns as arrays, and `update_columns`
on them as Python floats for action sets of fewer than `SMALL_SET` classifiers. A numpy call
costs about as much as twenty float operations whatever its length, and a multiplexer's action
set holds about five classifiers, so there the array form spends most of a trial on call
overhead. Both give the same numbers bit for bit: each classifier goes through the same IEEE
operations in the same order, the accuracies are summed in numpy's order (`numpy_sum`), and
the power of eq. 7.6 stays numpy's (its vectorised pow differs from C's in the last bit).
"""

from __future__ import annotations

from operator import add
from typing import NamedTuple

import numpy as np

from .xcs_params import Settings
from .xcs_population import (
    ERROR,
    EXPERIENCE,
    FITNESS,
    NUMEROSITY,
    PREDICTION,
    SET_SIZE,
    TIME_STAMP,
    Population,
)

_sum = np.add.reduce
"""The ufunc reduction itself: ndarray.sum adds a Python-level call per use."""
_CHANGED = EXPERIENCE + 1
"""The quantities UPDATE SET changes are the leading rows of `Population.stats` (numerosity
and time stamp follow)."""
SMALL_SET = 16
"""Action sets smaller than this are updated on Python floats (`update_columns`): fewer
instructions a trial than the array form on the 6- and the 11-multiplexer (8 and 32 cost
more on the 11); at most 128, the longest sum `numpy_sum` follows numpy through."""


def numpy_sum(values: list[float]) -> float:
    """The sum numpy's ``add.reduce`` gives for a contiguous float64 array of these values
    (at most 128 of them), term for term: its pairwise summation adds fewer than 8 terms left
    to right, more in 8 running sums over strides of 8 that it then adds pairwise, and the
    terms past the last whole stride left to right after those."""
    count = len(values)
    if count < 8:
        total = 0.0
        for value in values:
            total += value
        return total
    sums = values[:8]
    whole = count - count % 8
    for start in range(8, whole, 8):
        sums = list(map(add, sums, values[start:start + 8]))
    total = ((sums[0] + sums[1]) + (sums[2] + sums[3])) + ((sums[4] + sums[5])
                                                          + (sums[6] + sums[7]))
    for value in values[whole:]:
        total += value
    return total


class UpdateConstants(NamedTuple):
    """The update's constants as 0-d arrays: numpy converts a Python float on every array
    operation, which costs as much as a small operation itself."""

    one: np.ndarray
    beta: np.ndarray
    epsilon_0: np.ndarray
    accuracy_scale: np.ndarray
    """c = alpha ** (-1 / nu) / epsilon_0 of eq. 7.6 written as (error * c) ** -nu."""
    accuracy_floor: np.ndarray
    """c * epsilon_0: errors are clamped to it, so that an error of 0 raises no warning."""
    minus_nu: np.ndarray
    fitness_kept: np.ndarray
    """1 - beta_f (eq. 7.5)."""
    scale: float
    """accuracy_scale as a Python float, for `update_columns`."""
    floor: float
    """accuracy_floor as a Python float."""

    @classmethod
    def of(cls, settings: Settings) -> UpdateConstants:
        """The constants of checked settings."""
        scale = settings.alpha ** (-1.0 / settings.nu) / settings.epsilon_0
        return cls(*(np.array(value) for value in (
            1.0, settings.beta, settings.epsilon_0, scale, scale * settings.epsilon_0,
            -settings.nu, 1.0 - settings.beta_f)), scale, scale * settings.epsilon_0)


def update_set(stats: np.ndarray, set_size: float, payoff: float, settings: Settings,
               constant: UpdateConstants) -> None:
    """On an action set's columns of `Population.stats`, in place: eq. 7.1 (prediction), 7.4
    (error, against the updated prediction as in Butz & Wilson), the action-set size
    estimate, then fitness by eq. 7.5-7.7. Prediction, error and set size average over a
    classifier's first 1/beta updates (Wilson's MAM technique)."""
    experience = stats[EXPERIENCE]
    experience += constant.one
    rate = constant.one / experience
    numerosity = stats[NUMEROSITY]
    prediction, error, estimate = stats[PREDICTION], stats[ERROR], stats[SET_SIZE]
    if settings.beta_p == settings.beta_e == settings.beta:
        np.maximum(rate, constant.beta, out=rate)
        rate_p = rate_e = rate
    else:
        rate_p = np.maximum(rate, settings.beta_p)
        rate_e = np.maximum(rate, settings.beta_e)
        np.maximum(rate, settings.beta, out=rate)
    prediction += rate_p * (payoff - prediction)
    miss = np.abs(payoff - prediction)
    miss -= error
    error += rate_e * miss
    estimate += rate * (set_size - estimate)
    # eq. 7.6 as (error * c) ** -nu with c = alpha ** (-1 / nu) / epsilon_0, clamped so
    # that an error of 0 raises no warning; below epsilon_0 the accuracy is 1
    accuracy = error * constant.accuracy_scale
    np.maximum(accuracy, constant.accuracy_floor, out=accuracy)
    accuracy **= constant.minus_nu
    accuracy[error < constant.epsilon_0] = constant.one
    accuracy *= numerosity
    accuracy *= settings.beta_f / _sum(accuracy)  # beta_f * kappa', eq. 7.7
    fitness = stats[FITNESS]
    fitness *= constant.fitness_kept
    fitness += accuracy  # eq. 7.5


def update_columns(columns: list[list[float]], set_size: float, payoff: float,
                   settings: Settings, constant: UpdateConstants) -> None:
    """`update_set` on an action set's columns as Python lists (``stats.tolist()``), in
    place, for sets of fewer than `SMALL_SET` classifiers: per classifier the same
    operations in the same order, the accuracies summed in numpy's order, the power numpy's."""
    prediction, error, fitness, estimate, experience, numerosity, _ = columns
    beta, beta_p, beta_e = settings.beta, settings.beta_p, settings.beta_e
    epsilon_0, scale, floor = settings.epsilon_0, constant.scale, constant.floor
    accuracy = list(numerosity)  # an accuracy of 1 times the numerosity, unless inaccurate
    inaccurate, scaled = [], []
    for index, x in enumerate(experience):  # (indices: zip(..., strict=) costs a call's worth)
        x += 1.0
        rate = 1.0 / x
        p = prediction[index]
        p += (rate if rate > beta_p else beta_p) * (payoff - p)  # eq. 7.1
        e = error[index]
        e += (rate if rate > beta_e else beta_e) * (abs(payoff - p) - e)  # eq. 7.4
        a = estimate[index]
        a += (rate if rate > beta else beta) * (set_size - a)
        prediction[index], error[index], estimate[index], experience[index] = p, e, a, x
        if e >= epsilon_0:
            inaccurate.append(index)
            scaled.append(e * scale if e * scale > floor else floor)
    if inaccurate:  # eq. 7.6, by numpy's power
        powers = (np.array(scaled) ** constant.minus_nu).tolist()
        for index, power in enumerate(powers):
            accuracy[inaccurate[index]] *= power
    total = numpy_sum(accuracy)  # 0 only when every accuracy underflowed (huge rewards):
    # then numpy's IEEE division (inf and a warning), as the array form gives, not an error
    share = settings.beta_f / total if total else float(np.divide(settings.beta_f, total))
    kept = 1.0 - settings.beta_f
    for index, value in enumerate(accuracy):
        fitness[index] = fitness[index] * kept + value * share  # eq. 7.5


def update_action_set(population: Population, rows: np.ndarray, stats: np.ndarray,
                      payoff: float, settings: Settings, constant: UpdateConstants
                      ) -> tuple[list[float], list[float], list[float], float]:
    """UPDATE SET on the action set ``rows`` (``stats``: their columns of the population),
    written back to the population. Returns the set's numerosities, time stamps and updated
    fitnesses, and its size (the numerosities' sum: whole numbers, exact in any order)."""
    if rows.size < SMALL_SET:
        columns = stats.tolist()
        numerosity = columns[NUMEROSITY]
        set_size = float(sum(numerosity))
        update_columns(columns, set_size, payoff, settings, constant)
        prediction, error, fitness, estimate, experience = columns[:_CHANGED]
        population.write_columns(rows, prediction + error + fitness + estimate + experience,
                                 _CHANGED)
        return numerosity, columns[TIME_STAMP], fitness, set_size
    numerosity, stamps = stats[NUMEROSITY:TIME_STAMP + 1].tolist()  # (adjacent rows)
    set_size = float(sum(numerosity))
    update_set(stats, set_size, payoff, settings, constant)
    population.write_columns(rows, stats)
    return numerosity, stamps, stats[FITNESS].tolist(), set_size
