"""Part-based affordance models of thesis §5.4: data tuples, ĝ and ĥ, goal test and selection.

For one (part ψ, action type a) pair, ĝ maps the action parameter θ to the part's displacement
e_ψ (eq. 5.7, linear as 5.16) and ĥ maps e_ψ to the change of the object's state e_o (eq. 5.8,
linear as 5.17), both by least squares (eq. 5.18). A pair's models count as accurate once one
more sample changes neither residual sum of squares by δ3 or more (eq. 5.19).

``select_part_action`` is eq. 5.11 (with the tolerance δ1 of 5.10) and ``select_parameter`` is
eq. 5.12; ``OpeningGoal`` is the goal test 5.9. Everything here is numpy/scikit-learn only.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from numbers import Real

import numpy as np
from sklearn.base import BaseEstimator
from sklearn.utils import check_consistent_length
from sklearn.utils._param_validation import validate_params
from sklearn.utils.validation import check_is_fitted

from behaviours.learners.validation import POSITIVE, as_rows, check_bounds

Pair = tuple[str, str]
"""(part, action type)."""
Bounds = tuple[float, float]
"""Allowed action parameters lo < θ <= hi (m)."""


@dataclass(frozen=True)
class DataTuple:
    """One sample (o, s_o, ψ, s_ψ, a, θ, e_ψ, e_o) of eq. 5.6."""

    obj: str
    object_state: float  # s_o: the opening before the action (m)
    part: str
    part_state: tuple[float, ...]  # s_ψ: where the part was seen before the action
    action: str
    theta: float
    part_effect: float  # e_ψ: the part's displacement (eq. 5.15)
    object_effect: float  # e_o = s'_o - s_o (eq. 5.3)


def _column(values: object, name: str) -> np.ndarray:
    """``values`` as a finite 1-D float array (``check_array``; a scalar is one sample)."""
    return as_rows(values, name, 1)[:, 0]


def _line(x: np.ndarray, y: np.ndarray) -> tuple[float, float, float]:
    """(intercept, slope, RSS) of the least-squares line (eq. 5.18).

    With fewer than two distinct inputs the only line the data supports is the one through
    the origin, which is also what the physics says: no motion moves nothing, no displacement
    opens nothing. (An intercept fit would give a flat line, i.e. "θ does not matter".)
    The normal equations of a line in one input are solved directly, on centred data as
    scikit-learn's LinearRegression does: its input validation costs about 0.6 ms of CPU a
    call, which made refitting a known-object database of 150,000 models (two lines each)
    take three minutes of CPU (bench/objects_db.py).
    """
    if np.unique(x).size >= 2:
        x_mean, y_mean = x.mean(), y.mean()
        dx = x - x_mean
        slope = float(dx @ (y - y_mean) / (dx @ dx))
        intercept = float(y_mean - slope * x_mean)
    else:  # through the origin; all-zero inputs give the minimum-norm slope 0
        squares = float(x @ x)
        slope, intercept = (float(x @ y) / squares if squares else 0.0), 0.0
    residuals = y - (intercept + slope * x)
    return intercept, slope, float(residuals @ residuals)


class PartActionModel(BaseEstimator):
    """ĝ(θ) = b + c·θ (5.16) and ĥ(e_ψ) = d + e·e_ψ (5.17) of one (part, action) pair.

    ``partial_fit`` adds samples and refits both lines on everything seen; ``settled`` is the
    accuracy test 5.19 on both residual sums of squares. It has no parameters, and learns
    from (θ, e_ψ, e_o) triples rather than (X, y): scikit-learn's checks that need
    ``fit(X, y)`` do not apply.
    """

    def fit(self, theta: object, displacement: object, effect: object) -> PartActionModel:
        """Fit on exactly these samples, forgetting earlier ones."""
        self._forget()
        return self.partial_fit(theta, displacement, effect)

    def _forget(self) -> None:
        """Drop every sample and the RSS histories."""
        self.theta_, self.displacement_, self.effect_ = np.empty(0), np.empty(0), np.empty(0)
        self.g_rss_history_: list[float] = []
        self.h_rss_history_: list[float] = []

    def partial_fit(self, theta: object, displacement: object, effect: object) -> PartActionModel:
        """Add samples (θ, e_ψ, e_o) and refit ĝ and ĥ on all of them."""
        columns = [_column(theta, "theta"), _column(displacement, "displacement"),
                   _column(effect, "effect")]
        check_consistent_length(*columns)
        if not hasattr(self, "theta_"):
            self._forget()
        self.theta_ = np.concatenate([self.theta_, columns[0]])
        self.displacement_ = np.concatenate([self.displacement_, columns[1]])
        self.effect_ = np.concatenate([self.effect_, columns[2]])
        self.g_intercept_, self.g_slope_, g_rss = _line(self.theta_, self.displacement_)
        self.h_intercept_, self.h_slope_, h_rss = _line(self.displacement_, self.effect_)
        self.g_rss_history_.append(g_rss)
        self.h_rss_history_.append(h_rss)
        self.n_samples_ = int(self.theta_.size)
        return self

    def _check_fitted(self) -> None:
        check_is_fitted(self, "g_slope_")

    def predict_displacement(self, theta: object) -> np.ndarray:
        """ĝ(θ): the predicted displacement of the part (eq. 5.7)."""
        self._check_fitted()
        return self.g_intercept_ + self.g_slope_ * _column(theta, "theta")

    def predict_effect(self, displacement: object) -> np.ndarray:
        """ĥ(e_ψ): the predicted change of the object's state (eq. 5.8)."""
        self._check_fitted()
        return self.h_intercept_ + self.h_slope_ * _column(displacement, "displacement")

    def predict(self, theta: object) -> np.ndarray:
        """ĥ(ĝ(θ)): the predicted change of the object's state for action parameter θ."""
        return self.predict_effect(self.predict_displacement(theta))

    def settled(self, tol: float) -> bool:
        """Eq. 5.19 on ĝ and ĥ: the last sample changed neither RSS by ``tol`` or more."""
        histories = (getattr(self, "g_rss_history_", []), getattr(self, "h_rss_history_", []))
        return all(len(h) >= 2 and abs(h[-1] - h[-2]) < tol for h in histories)

    def displacement_range(self, bounds: Bounds) -> tuple[float, float]:
        """The displacements ĝ predicts over lo..hi, lowest first (the reachable E_ψ)."""
        ends = self.predict_displacement(list(check_bounds(bounds)))
        return float(ends.min()), float(ends.max())

    def moves(self, bounds: Bounds, min_displacement: float) -> bool:
        """Whether ĝ predicts a displacement of at least ``min_displacement`` somewhere in Θ."""
        low, high = self.displacement_range(bounds)
        return max(abs(low), abs(high)) >= min_displacement


AIMS = ("goal", "goal_plus_delta1")
"""What selection (5.10, 5.11) aims at: s_o^g as printed, or s_o^g + δ1."""


@dataclass(frozen=True)
class OpeningGoal:
    """The goal s_o^g of the lid task and the test 5.9 (thesis §5.6.1: s_o^g = 0.1 m).

    Reached when s_o >= s_o^g: §5.6.2 counts 0.14 m as achieving 0.1 m, like eq. 6.9 ("opened
    wide enough"). Selection (5.10, 5.11) accepts predictions within δ1 of what it aims at:
    ``aim="goal"`` is eq. 5.10 as printed, ĥ(e_ψ) against s_o^g − s_o^i; ``"goal_plus_delta1"``
    aims δ1 higher, so a model's small error does not leave the object just short of a goal
    tested one-sidedly: with δ1 = 0.02, o1's saturating lid (0.11 m from θ = 0.05 on) made one
    seed in eight transfer a θ* that opened o3 to 0.098 m; with 0.03 all eight opened it with
    one action.
    """

    goal: float = 0.1
    delta1: float = 0.03
    aim: str = "goal_plus_delta1"

    def __post_init__(self) -> None:
        if not (isinstance(self.goal, (int, float)) and math.isfinite(self.goal)):
            raise ValueError(f"goal must be a finite number, got {self.goal!r}")
        if not (isinstance(self.delta1, (int, float)) and 0 <= self.delta1 < math.inf):
            raise ValueError(f"delta1 must be a finite number >= 0, got {self.delta1!r}")
        if self.aim not in AIMS:
            raise ValueError(f"aim must be one of {', '.join(AIMS)}, got {self.aim!r}")

    def reached(self, state: float) -> bool:
        """Eq. 5.9 (one-sided, see the class docstring)."""
        return state >= self.goal

    @property
    def target(self) -> float:
        """The state selection aims at: s_o^g, or s_o^g + δ1."""
        return self.goal + (self.delta1 if self.aim == "goal_plus_delta1" else 0.0)

    def desired_effect(self, initial_state: float) -> float:
        """The change of state 5.10 aims at: the target less s_o^i."""
        return self.target - initial_state


@dataclass(frozen=True)
class FunctionalPair:
    """The part, action type and θ that achieved the goal (the thesis's ψ*, a*, θ*)."""

    part: str
    action: str
    theta: float


@dataclass(frozen=True)
class Selection:
    """A pair chosen by eq. 5.11 with its target displacement e_ψ* and θ* of eq. 5.12."""

    part: str
    action: str
    displacement: float  # e_ψ*
    error: float  # |ĥ(e_ψ*) - (s_o^g - s_o^i)|, the value minimised in 5.11
    theta: float | None  # θ* (None: no θ in Θ gives e_ψ* within δ2)

    @property
    def pair(self) -> Pair:
        return self.part, self.action


@validate_params({"model": [PartActionModel], "displacement": [Real], "bounds": "no_validation",
                  "delta2": [POSITIVE]}, prefer_skip_nested_validation=True)
def select_parameter(
    model: PartActionModel, displacement: float, bounds: Bounds, delta2: float
) -> float | None:
    """Eq. 5.12: the smallest θ in lo < θ <= hi with |ĝ(θ) - e_ψ*| <= δ2, or None if none.

    θ is one number per action type here (the arm moves along the type's direction), so ‖θ‖ is
    |θ|; the bounds are non-negative in every use, so the smallest |θ| is the smallest θ.
    The open lower end is approached to within a thousandth of the range.
    """
    low, high = check_bounds(bounds)
    b, c = model.g_intercept_, model.g_slope_
    floor = low + (high - low) * 1e-3
    if c == 0.0:
        return floor if abs(b - displacement) <= delta2 else None
    ends = sorted(((displacement - delta2 - b) / c, (displacement + delta2 - b) / c))
    theta = max(ends[0], floor)
    return float(theta) if theta <= min(ends[1], high) else None


def select_part_action(
    models: Mapping[Pair, PartActionModel],
    bounds: Mapping[str, Bounds],
    desired_effect: float,
    *,
    delta1: float,
    delta2: float,
    exclude: frozenset[Pair] | set[Pair] = frozenset(),
) -> Selection | None:
    """Eq. 5.11: the pair and e_ψ whose ĥ(e_ψ) comes closest to the desired change of state.

    e_ψ ranges over what ĝ predicts in Θ (a part cannot be moved further than the arm moves
    it). Pairs whose prediction lies within δ1 of the desired effect (5.10) are equally good;
    among them the one with the smallest θ* (5.12) wins, like 5.12 prefers the smallest motion.
    Returns None when there is no model to choose from.
    """
    candidates: list[tuple[tuple[float, float], Selection]] = []
    for (part, action), model in models.items():
        if (part, action) in exclude:
            continue
        if action not in bounds:
            raise ValueError(f"no parameter bounds for action {action!r}")
        low, high = model.displacement_range(bounds[action])
        if model.h_slope_ != 0.0:
            target = (desired_effect - model.h_intercept_) / model.h_slope_
        else:
            target = high
        displacement = float(min(max(target, low), high))
        error = abs(float(model.predict_effect(displacement)[0]) - desired_effect)
        theta = select_parameter(model, displacement, bounds[action], delta2)
        selection = Selection(part, action, displacement, error, theta)
        within = error <= delta1
        key = (0.0 if within else error, theta if theta is not None else math.inf)
        candidates.append((key, selection))
    if not candidates:
        return None
    return min(candidates, key=lambda item: item[0])[1]
