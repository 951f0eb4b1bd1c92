"""The thesis's stop test (4.10)–(4.11) evaluated on a recorded TD-error series, beside
labelled VARIANTS of it that are NOT the thesis's.

The thesis (§4.4.3, §4.6.1): with δ̄^k = (1/N) Σ_{i=k−N+1..k} |δ^i| (4.11), Algorithm 3 stops
at the first step k where

    thesis:            |δ̄^k − δ̄^(k−1)| < ε                                    (4.10)

(k ≥ N + 1, N = 20, ε = 1e−4). ``cacla.TDConvergence`` applies it online inside Algorithm 3;
here it is applied after the fact to a whole series, so that several criteria can be judged
on the same runs without simulating again. The variants keep N and ε and change only when, or
what, (4.10) compares (issue 10: the owner decides whether any replaces the thesis's):

    after-transient:   the first k ≥ 2N + 1 with |δ̄^k − δ̄^(k−1)| < ε
                       (both averages over steps after the first N random actions)
    sustained:         the first k with |δ̄^j − δ̄^(j−1)| < ε for every j in k−N+1..k
                       ((4.10) at N consecutive steps; so k ≥ 2N)
    window-to-window:  the first k ≥ 2N with |δ̄^k − δ̄^(k−N)| < ε
                       (two consecutive, non-overlapping window averages agree)

Hand-written (a few numpy lines): no library offers these stopping rules.
"""

from __future__ import annotations

import numpy as np
from sklearn.utils import check_array
from sklearn.utils._param_validation import StrOptions, validate_params

from behaviours.learners.validation import POSITIVE, POSITIVE_INT

__all__ = ["CRITERIA", "VARIANTS", "averaged_magnitudes", "first_convergence", "holds"]

CRITERIA = ("thesis", "after-transient", "sustained", "window-to-window")
"""The thesis's (4.10) first, then the variants."""
VARIANTS = CRITERIA[1:]
"""The criteria that depart from the thesis."""


@validate_params({"td_errors": ["array-like"], "window": [POSITIVE_INT]},
                 prefer_skip_nested_validation=True)
def averaged_magnitudes(td_errors: object, window: int = 20) -> np.ndarray:
    """δ̄^k (4.11) for k = 1..n: the mean |δ| of the last ``window`` steps, NaN for k < N."""
    deltas = _series(td_errors)
    size = int(window)
    averaged = np.full(deltas.size, np.nan)
    if deltas.size >= size:
        windows = np.lib.stride_tricks.sliding_window_view(np.abs(deltas), size)
        averaged[size - 1:] = windows.mean(axis=1)
    return averaged


@validate_params({"td_errors": ["array-like"], "criterion": [StrOptions(set(CRITERIA))],
                  "window": [POSITIVE_INT], "tol": [POSITIVE]},
                 prefer_skip_nested_validation=True)
def holds(td_errors: object, criterion: str, window: int = 20,
          tol: float = 1e-4) -> np.ndarray:
    """For each step k = 1..n, whether ``criterion`` holds at k (a boolean array)."""
    size, eps = int(window), float(tol)
    averaged = averaged_magnitudes(td_errors, size)
    steps = np.arange(1, averaged.size + 1)
    if criterion == "window-to-window":
        return _below(_lagged_change(averaged, size), eps) & (steps >= 2 * size)
    each = _below(_lagged_change(averaged, 1), eps)  # (4.10) at k, from k = N + 1
    if criterion == "thesis":
        return each
    if criterion == "after-transient":
        return each & (steps >= 2 * size + 1)
    return _run_lengths(each) >= size  # sustained


def first_convergence(td_errors: object, criterion: str, window: int = 20,
                      tol: float = 1e-4) -> int | None:
    """The first step k (1-based) at which ``criterion`` holds, None if it never does:
    where Algorithm 3 would stop under that criterion."""
    met = np.flatnonzero(holds(td_errors, criterion, window, tol))
    return int(met[0]) + 1 if met.size else None


def _series(td_errors: object) -> np.ndarray:
    """A TD-error series as a finite 1-D float array (``check_array``), or a clear error."""
    deltas = check_array(td_errors, ensure_2d=False, dtype=np.float64, input_name="td_errors",
                         ensure_min_samples=0)
    if deltas.ndim != 1:
        raise ValueError(f"TD errors must be a 1-D series, got shape {deltas.shape}")
    return deltas


def _lagged_change(averaged: np.ndarray, lag: int) -> np.ndarray:
    """|δ̄^k − δ̄^(k−lag)| at each k, NaN where either is undefined."""
    change = np.full(averaged.size, np.nan)
    if averaged.size > lag:
        change[lag:] = np.abs(averaged[lag:] - averaged[:-lag])
    return change


def _below(values: np.ndarray, eps: float) -> np.ndarray:
    """values < eps, False where a value is NaN (the test cannot be made yet)."""
    return np.nan_to_num(values, nan=np.inf) < eps


def _run_lengths(flags: np.ndarray) -> np.ndarray:
    """At each position, how many consecutive True values end there."""
    runs = np.zeros(flags.size, dtype=int)
    count = 0
    for index, flag in enumerate(flags):
        count = count + 1 if flag else 0
        runs[index] = count
    return runs
