"""Algorithm 4 (thesis §5.4.3): learn every part × every action type, then use the models.

``Session`` is what both Algorithm 4 and Algorithm 6 do on an object: act through the
object's ``perform`` (every physical action becomes a ``Trial``, so N of eq. 5.13 is just
their number), keep the data tuples 5.6 and one ``PartActionModel`` per pair, explore a pair
with random θ until n samples or until its model settles (5.19) as ineffective, and exploit
the models with 5.11/5.12. ``PartBasedLearner`` is Algorithm 4 as a scikit-learn-style
estimator: ``fit(obj)`` explores and then acts with the selected pair until the goal test 5.9
passes (at most ``max_checks`` times, each failure adding its sample to the pair's data).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from numbers import Integral, Real
from typing import ClassVar

import numpy as np
from sklearn.base import BaseEstimator
from sklearn.utils import check_random_state
from sklearn.utils._param_validation import Interval, StrOptions

from behaviours.learners.part_models import (
    AIMS,
    Bounds,
    DataTuple,
    FunctionalPair,
    OpeningGoal,
    Pair,
    PartActionModel,
    Selection,
    check_bounds,
    select_part_action,
)
from behaviours.learners.protocol import ObjectUnderTest, ObjectView, Trial
from behaviours.learners.validation import POSITIVE, POSITIVE_INT


@dataclass(frozen=True)
class SessionParams:
    """The learners' shared parameters, checked once (see ``PartBasedLearner``)."""

    n: int
    n_min: int
    settle_tol: float
    min_displacement: float
    goal: OpeningGoal
    delta2: float
    max_checks: int

    @classmethod
    def from_estimator(cls, est: BaseEstimator) -> SessionParams:
        """An estimator's parameters, checked by its ``_parameter_constraints``."""
        est._validate_params()  # type: ignore[attr-defined]
        p = est.get_params()
        return cls(int(p["n"]), int(p["n_min"]), float(p["settle_tol"]),
                   float(p["min_displacement"]), OpeningGoal(p["goal"], p["delta1"], p["aim"]),
                   float(p["delta2"]), int(p["max_checks"]))


class Session:
    """One learning episode on one object: its trials, data tuples and pair models."""

    def __init__(self, obj: ObjectUnderTest, params: SessionParams,
                 rng: np.random.RandomState) -> None:
        self.obj = obj
        self.params = params
        self.rng = rng
        self.bounds: dict[str, Bounds] = {
            action: check_bounds(b, f"bounds of action {action!r}")
            for action, b in dict(obj.actions).items()
        }
        if not self.bounds:
            raise ValueError(f"object {obj.name!r} offers no action types")
        self.view: ObjectView = obj.perceive()
        if not self.view.parts:
            raise ValueError(f"no part of object {obj.name!r} is perceived")
        self.initial_state = float(self.view.state)
        self.models: dict[Pair, PartActionModel] = {}
        self.data: list[DataTuple] = []
        self.trials: list[Trial] = []
        self.success: Trial | None = None

    @property
    def reached(self) -> bool:
        """Whether some action has achieved the goal (5.9)."""
        return self.success is not None

    def act(self, part: str, action: str, theta: float, purpose: str) -> Trial:
        """Perform action(θ) on part, record the data tuple and trial, refit the pair's model."""
        if part not in self.view.parts:
            raise ValueError(f"object {self.obj.name!r} has no part {part!r}")
        low, high = self.bounds[action]
        if not low < theta <= high:
            raise ValueError(f"theta {theta} out of bounds {low} < theta <= {high} for {action}")
        outcome = self.obj.perform(part, action, float(theta))
        displacement, effect = float(outcome.part_displacement), float(outcome.effect)
        if not (math.isfinite(displacement) and math.isfinite(effect)):
            raise ValueError(f"object {self.obj.name!r} reported a non-finite outcome {outcome}")
        self.data.append(DataTuple(self.obj.name, float(outcome.state_before), part,
                                   tuple(self.view.positions.get(part, ())), action, float(theta),
                                   displacement, effect))
        model = self.models.setdefault((part, action), PartActionModel())
        model.partial_fit([theta], [displacement], [effect])
        reached = self.params.goal.reached(float(outcome.state_after))
        trial = Trial(part, action, float(theta), displacement, effect,
                      float(outcome.state_after), purpose, reached)
        self.trials.append(trial)
        if reached and self.success is None:
            self.success = trial
        return trial

    def random_theta(self, action: str) -> float:
        """θ drawn uniformly in lo < θ <= hi."""
        low, high = self.bounds[action]
        return high - float(self.rng.uniform(0.0, high - low))

    def dead(self, pair: Pair) -> bool:
        """The pair's model has settled (5.19) on no significant displacement of the part."""
        model = self.models.get(pair)
        p = self.params
        return (model is not None and model.n_samples_ >= p.n_min
                and model.settled(p.settle_tol)
                and not model.moves(self.bounds[pair[1]], p.min_displacement))

    def explore_pair(self, part: str, action: str, stop_at_goal: bool) -> None:
        """Algorithm 4 lines 3-8: random θ until the pair holds n samples or is dead."""
        while True:
            model = self.models.get((part, action))
            if (model is not None and model.n_samples_ >= self.params.n) or self.dead(
                    (part, action)):
                return
            self.act(part, action, self.random_theta(action), "explore")
            if stop_at_goal and self.reached:
                return

    def select(self, pairs: Iterable[Pair] | None = None) -> Selection | None:
        """Eq. 5.11 and 5.12 over this object's own models (or over ``pairs`` of them)."""
        chosen = self.models if pairs is None else {
            p: self.models[p] for p in pairs if p in self.models}
        return select_part_action(
            chosen, self.bounds, self.params.goal.desired_effect(self.initial_state),
            delta1=self.params.goal.delta1, delta2=self.params.delta2)

    def predicts_goal(self, selection: Selection | None) -> bool:
        """Whether a selection's pair is predicted to reach the goal (5.10) with a valid θ*."""
        return (selection is not None and selection.theta is not None
                and selection.error <= self.params.goal.delta1)

    def exploit(self, pairs: Iterable[Pair] | None = None, only_if_predicted: bool = False,
                checks: int = 1) -> Trial | None:
        """Act with the selected pair and θ* until an action reaches the goal (5.9), at most
        ``checks`` times; return that action's trial, or None.

        With ``only_if_predicted`` nothing is done unless the models predict the goal (5.10);
        a failed check's sample joins the pair's data and the selection is made again.
        """
        pool = None if pairs is None else list(pairs)
        for _ in range(checks):
            selection = self.select(pool)
            if selection is None or (only_if_predicted and not self.predicts_goal(selection)):
                return None
            low, high = self.bounds[selection.action]
            theta = selection.theta if selection.theta is not None else high
            trial = self.act(selection.part, selection.action, theta, "exploit")
            if trial.reached:
                return trial
        return None


class PartBasedLearner(BaseEstimator):
    """Algorithm 4: every part × every action type (n samples, early stop when dead), then use.

    Parameters: ``n`` samples per pair at most (thesis n = 5); ``n_min`` samples before the
    settling test 5.19 (two points always fit a line, so three are the first test: the thesis
    needed three sweeps to call a pair ineffective); ``settle_tol`` δ3 (m²);
    ``min_displacement`` (m) below which a part counts as not moved; ``goal`` s_o^g and
    ``delta1`` (5.9, 5.10) and ``aim`` (what 5.10 aims at, see ``OpeningGoal``); ``delta2``
    (5.12); ``max_checks`` goal-directed actions at most.

    After ``fit(obj)``: ``models_`` {(part, action): PartActionModel}, ``trials_`` every action
    taken, ``n_actions_`` their number (N of Table 5.4, the goal-directed actions included),
    ``functional_`` the pair selected by 5.11 whose action (θ* of 5.12) achieved the goal
    (None if no check did), ``data_`` the data tuples 5.6.

    It learns by acting on an object (``fit(obj)``), not from (X, y): scikit-learn's checks
    that need ``fit(X, y)`` do not apply.
    """

    _parameter_constraints: ClassVar[dict[str, list]] = {
        "n": [POSITIVE_INT], "n_min": [Interval(Integral, 2, None, closed="left")],
        "settle_tol": [POSITIVE], "min_displacement": [POSITIVE],
        "goal": [Interval(Real, None, None, closed="neither")],
        "delta1": [Interval(Real, 0.0, None, closed="left")], "aim": [StrOptions(set(AIMS))],
        "delta2": [POSITIVE],
        "max_checks": [POSITIVE_INT], "random_state": ["random_state"],
    }

    def __init__(self, n: int = 5, n_min: int = 3, settle_tol: float = 1e-4,
                 min_displacement: float = 0.01, goal: float = 0.1, delta1: float = 0.03,
                 delta2: float = 0.002, max_checks: int = 3, aim: str = "goal_plus_delta1",
                 random_state: int | np.random.RandomState | None = None) -> None:
        self.n = n
        self.n_min = n_min
        self.settle_tol = settle_tol
        self.min_displacement = min_displacement
        self.goal = goal
        self.delta1 = delta1
        self.aim = aim
        self.delta2 = delta2
        self.max_checks = max_checks
        self.random_state = random_state

    def _start(self, obj: ObjectUnderTest) -> Session:
        """A fresh session on obj with validated parameters."""
        return Session(obj, SessionParams.from_estimator(self),
                       check_random_state(self.random_state))

    def fit(self, obj: ObjectUnderTest) -> PartBasedLearner:
        """Run Algorithm 4 on ``obj``."""
        session = self._start(obj)
        for part in session.view.parts:
            for action in session.bounds:
                session.explore_pair(part, action, stop_at_goal=False)
        found = session.exploit(checks=session.params.max_checks)
        self._finish(session, found)
        return self

    def _finish(self, session: Session, found: Trial | None) -> None:
        """Copy the session's results into the fitted attributes."""
        self.view_ = session.view
        self.bounds_ = dict(session.bounds)
        self.models_ = dict(session.models)
        self.trials_ = list(session.trials)
        self.data_ = list(session.data)
        self.n_actions_ = len(session.trials)
        self.functional_ = (None if found is None
                            else FunctionalPair(found.part, found.action, found.theta))
