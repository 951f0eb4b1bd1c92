"""Input checks shared by the continuous learners: finite arrays, shapes, action bounds.

Every check raises ``ValueError`` with a message naming the argument, so a caller (an
environment, a CLI) can show it as is.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

__all__ = ["ActionBounds", "as_rows", "check_positive", "check_rate"]


def as_rows(values: object, name: str, width: int | None = None) -> np.ndarray:
    """``values`` as a finite 2-D float array (a 1-D input is one column; a scalar one cell)."""
    try:
        array = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be numbers, got {values!r}") from None
    if array.ndim == 0:
        array = array.reshape(1, 1)
    elif array.ndim == 1:
        array = array[:, None]
    if array.ndim != 2 or array.shape[0] == 0:
        raise ValueError(f"{name} must be a non-empty 2-D array of rows, got shape {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} contains a value that is not a finite number (NaN or inf)")
    if width is not None and array.shape[1] != width:
        raise ValueError(f"{name} must have {width} column(s), got {array.shape[1]}")
    return array


def check_rate(value: object, name: str) -> float:
    """A step size or discount in [0, 1]."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0 <= value <= 1:
        raise ValueError(f"{name} must be a number in [0, 1], got {value!r}")
    return float(value)


def check_positive(value: object, name: str, *, integer: bool = False) -> float:
    """A positive (whole, if ``integer``) number."""
    kinds = (int, np.integer) if integer else (int, float, np.integer, np.floating)
    if isinstance(value, bool) or not isinstance(value, kinds) or not (
            math.isfinite(value) and value > 0):
        what = "a positive whole number" if integer else "a positive number"
        raise ValueError(f"{name} must be {what}, got {value!r}")
    return value  # type: ignore[return-value]


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
        rows = self.check(actions, name)
        return np.clip(2.0 * (rows - self.low) / (self.high - self.low) - 1.0, -1.0, 1.0)

    def from_unit(self, unit: np.ndarray) -> np.ndarray:
        """[−1, 1] per dimension → physical actions (values outside are clipped first)."""
        clipped = np.clip(np.asarray(unit, dtype=float), -1.0, 1.0)
        return self.low + (clipped + 1.0) / 2.0 * (self.high - self.low)

    def as_list(self) -> list[list[float]]:
        """The bounds as [[lo, hi], ...] (JSON-ready, and how errors show them)."""
        return [[float(lo), float(hi)] for lo, hi in zip(self.low, self.high, strict=True)]
