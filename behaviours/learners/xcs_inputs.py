"""Checking the arguments of one XCS step (`XCS.act`, `XCS.reward`): a state of 0/1 bits, a set
of allowed actions, a finite reward and a done flag, each a ValueError naming the argument.

Written by hand rather than with scikit-learn's validators, which cost a fifth of a multiplexer
trial each: these run at every step (the learner's parameters, checked once, use scikit-learn).
"""

from __future__ import annotations

import math
import numbers
import reprlib
from collections.abc import Iterable

import numpy as np


def state_bits(state: object) -> np.ndarray:
    """A state ("0101", or a sequence of 0/1) as a non-empty array of bits."""
    if isinstance(state, str):
        bits = np.frombuffer(state.encode("utf-8"), np.uint8) - np.uint8(48)
    else:
        try:
            array = np.asarray(state)
        except (TypeError, ValueError):
            array = np.asarray([None])
        if array.ndim != 1 or array.dtype.kind not in "biuf":
            raise ValueError(f"state must be a string or sequence of 0/1, got "
                             f"{reprlib.repr(state)}")
        bits = array.astype(np.uint8) if np.isin(array, (0, 1)).all() else np.array([2])
    if bits.size == 0 or bits.max() > 1:
        raise ValueError(f"state must be a non-empty string or sequence of 0/1 bits, got "
                         f"{reprlib.repr(state)}")
    return bits


def permitted_actions(allowed: Iterable[int], n_actions: int) -> np.ndarray:
    """The allowed action indices (0..n_actions-1, at least one) as a sorted array."""
    if isinstance(allowed, str | bytes) or not isinstance(allowed, Iterable):
        raise ValueError(f"allowed must be a set of action indices, got {allowed!r}")
    actions = list(allowed)
    for action in actions:
        if (isinstance(action, bool) or not isinstance(action, int | np.integer)
                or not 0 <= action < n_actions):
            raise ValueError(f"allowed: {action!r} is not an action index "
                             f"0..{n_actions - 1}")
    if not actions:
        raise ValueError("allowed must hold at least one action")
    return np.unique(np.array(actions, np.int64))


def check_reward(r: object, done: object) -> None:
    """A finite reward and a True/False ``done``."""
    if type(r) is not float and (not isinstance(r, numbers.Real) or isinstance(r, bool)):
        raise ValueError(f"r must be a finite number, got {r!r}")
    if not math.isfinite(r):
        raise ValueError(f"r must be a finite number, got {r!r}")
    if done is not True and done is not False and not isinstance(done, np.bool_):
        raise ValueError(f"done must be True or False, got {done!r}")
