"""UPDATE SET of XCS (Butz & Wilson 2001; thesis eq. 7.1, 7.4-7.7): the reinforcement
component's arithmetic on one action set's columns of `Population.stats`, in place."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .xcs_params import Settings
from .xcs_population import ERROR, EXPERIENCE, FITNESS, NUMEROSITY, PREDICTION, SET_SIZE

_sum = np.add.reduce
"""The ufunc reduction itself: ndarray.sum adds a Python-level call per use."""


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

    @classmethod
    def of(cls, settings: Settings) -> UpdateConstants:
        """The constants of checked settings."""
        scale = settings.alpha ** (-1.0 / settings.nu) / settings.epsilon_0
        return cls(*(np.array(value) for value in (
            1.0, settings.beta, settings.epsilon_0, scale, scale * settings.epsilon_0,
            -settings.nu, 1.0 - settings.beta_f)))


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
