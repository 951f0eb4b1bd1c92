"""Input checks shared by the continuous learners: rows of finite numbers, action bounds.

``as_rows`` is scikit-learn's ``check_array`` with the continuous learners' shapes (a number is
one sample of one value, a 1-D array one value per sample), so every refusal is scikit-learn's
ValueError naming the argument. ``ActionBounds`` checks a learner's action space (lo < hi per
dimension, a domain rule no scikit-learn constraint states) and maps actions to [−1, 1].
Parameters of functions are checked by scikit-learn's ``validate_params`` where they are
defined; ``POSITIVE_INT`` and ``POSITIVE`` are the constraints they share.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from numbers import Integral, Real

import numpy as np
from sklearn.utils import check_array
from sklearn.utils._param_validation import Interval

__all__ = ["POSITIVE", "POSITIVE_INT", "RATE", "ActionBounds", "as_rows", "check_bounds"]

POSITIVE_INT = Interval(Integral, 1, None, closed="left")
POSITIVE = Interval(Real, 0.0, None, closed="neither")
"""A finite number > 0 (scikit-learn's intervals refuse NaN, and inf when open-ended)."""
RATE = Interval(Real, 0.0, 1.0, closed="both")
"""A step size or discount in [0, 1]."""


def as_rows(values: object, name: str, width: int | None = None) -> np.ndarray:
    """``values`` as a finite 2-D float array (a 1-D input is one column; a scalar one cell),
    checked by ``check_array``; ``width`` columns if given."""
    array = check_array(values, ensure_2d=False, dtype=np.float64, input_name=name,
                        ensure_min_samples=0)
    if array.ndim < 2:
        array = array.reshape(-1, 1)
    if array.shape[0] == 0:
        raise ValueError(f"{name} must hold at least one row, got shape {array.shape}")
    if width is not None and array.shape[1] != width:
        raise ValueError(f"{name} must have {width} column(s), got {array.shape[1]}")
    return array


def check_bounds(bounds: object, what: str = "bounds") -> tuple[float, float]:
    """``bounds`` as finite floats (lo, hi) with lo < hi, or a ValueError naming ``what``:
    one action parameter's range (the domain rule no scikit-learn constraint states)."""
    try:
        low, high = (float(b) for b in bounds)  # type: ignore[union-attr]
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be a (low, high) pair of numbers, got {bounds!r}") from None
    if not (math.isfinite(low) and math.isfinite(high) and low < high):
        raise ValueError(f"{what} must be finite with low < high, got ({low}, {high})")
    return low, high


class ActionBounds:
    """Per-dimension bounds [lo, hi] of a continuous action, and the map to [−1, 1] (§4.6.1)."""

    def __init__(self, bounds: Sequence[Sequence[float]]) -> None:
        """``bounds`` is one (lo, hi) pair per action dimension, lo < hi, all finite."""
        try:
            array = np.asarray(bounds, dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"action bounds must be (lo, hi) pairs, got {bounds!r}") from None
        if array.ndim != 2 or array.shape[1] != 2 or array.shape[0] == 0:
            raise ValueError(f"action bounds must be one (lo, hi) pair per dimension, "
                             f"got {bounds!r}")
        if not np.all(np.isfinite(array)) or not np.all(array[:, 0] < array[:, 1]):
            raise ValueError(f"action bounds must be finite with lo < hi, got {bounds!r}")
        self.low = array[:, 0].copy()
        self.high = array[:, 1].copy()

    @property
    def dims(self) -> int:
        """Number of action dimensions."""
        return int(self.low.size)

    def check(self, actions: object, name: str = "actions") -> np.ndarray:
        """Rows of physical actions, refused (ValueError) if any lies outside the bounds."""
        rows = as_rows(actions, name, self.dims)
        slack = 1e-12 * (self.high - self.low)
        if np.any(rows < self.low - slack) or np.any(rows > self.high + slack):
            raise ValueError(f"{name} out of bounds: every dimension must lie in "
                             f"{self.as_list()}, got {rows.tolist()}")
        return rows

    def to_unit(self, actions: object, name: str = "actions") -> np.ndarray:
        """Physical actions → [−1, 1] per dimension (checked against the bounds)."""
        return self.unit_rows(self.check(actions, name))

    def unit_rows(self, rows: np.ndarray) -> np.ndarray:
        """``to_unit`` of rows already known to be float rows within the bounds (unchecked:
        for a learner's own loop, whose actions ``from_unit`` made)."""
        return np.clip(2.0 * (rows - self.low) / (self.high - self.low) - 1.0, -1.0, 1.0)

    def from_unit(self, unit: np.ndarray) -> np.ndarray:
        """[−1, 1] per dimension → physical actions (values outside are clipped first)."""
        clipped = np.clip(np.asarray(unit, dtype=float), -1.0, 1.0)
        return self.low + (clipped + 1.0) / 2.0 * (self.high - self.low)

    def as_list(self) -> list[list[float]]:
        """The bounds as [[lo, hi], ...] (JSON-ready, and how errors show them)."""
        return [[float(lo), float(hi)] for lo, hi in zip(self.low, self.high, strict=True)]
