"""Algorithm 6 (thesis §5.5.4): transfer learning of affordances from a known source object.

``TransferLearner.fit(obj)`` picks the most similar known object with Algorithm 5 and then:
1. exploits the source's functional pair on the target's look-alike part (lines 2-11), with
   θ stepped along the source model's gradient while the goal is not reached (line 13) and a
   last try with the target's own model (line 16);
2. tries every other action type once on that part with the largest θ and compares the
   part's displacement with what the source's model predicts (lines 17-23); only an
   inconsistent observation where the part really moved is followed up by more samples and a
   goal-directed action with the target's model (lines 20-21);
3. does the same with every action on the target's parts that look like the source's other
   parts (lines 24-30);
4. runs Algorithm 4 on the parts left, which look novel (line 31).
The run ends as soon as any action achieves the goal (5.9): transfer aims at the goal, not at
every model (§5.5.1: "The purpose is not to learn every prediction model ... but is to achieve
the goal condition (5.9) as fast as possible"). Line 31's Algorithm 4 stops at the goal too
unless ``stop_at_goal`` is False: Algorithm 4 as printed explores every pair before it
selects. With no relevant source it is Algorithm 4 exactly. ``branch_`` says which of these
found the goal: direct, gradient, other_action, other_part, fallback, no_source, or failed
(nothing did, or ``other_parts=False`` stopped it after the source's functional part).

Choices the thesis leaves open, made here: λ_k of line 13 is the step after which the source's
models predict the goal's opening (a Newton step on ĥ∘ĝ of the source, clipped to Θ); the loop
of lines 9-15 also ends once the pair's model settles as ineffective (as in Algorithm 4) or θ
cannot move further; line 16 acts only when the target's model predicts the goal; the one θ̃
of line 18 is the largest allowed, where a difference in displacement shows best.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import ClassVar

import numpy as np

from behaviours.learners.baseline import PartBasedLearner, Session
from behaviours.learners.known_objects import KnownObject
from behaviours.learners.part_models import Bounds, OpeningGoal, PartActionModel, Selection
from behaviours.learners.similarity import (
    DEFAULT_WEIGHTS,
    PartSimilarity,
    SourceCandidate,
    fit_similarity,
    rank_sources,
    similar_part,
)
from behaviours.learners.validation import POSITIVE, POSITIVE_INT

BRANCHES = ("direct", "gradient", "other_action", "other_part", "fallback", "no_source",
            "failed")


def gradient_step(theta: float, source: PartActionModel, state_after: float,
                  goal: OpeningGoal, bounds: Bounds) -> float | None:
    """Line 13: θ + λ·∇ĝ_src(θ), λ > 0 chosen so the source predicts the missing opening.

    The source's ĥ slope turns the opening still missing into a displacement, the gradient c
    of ĝ_src into a step of θ (λ = Δe_ψ / c²); the result is clipped into Θ. None when the
    source's ĝ is flat or θ cannot move (it already sits at the bound the step points to).
    """
    low, high = bounds
    slope = source.g_slope_
    if slope == 0.0:
        return None
    missing = goal.target - state_after
    if source.h_slope_ > 0.0 and missing > 0.0:
        step = missing / source.h_slope_ / slope  # = λ·c with λ = Δe_ψ / c²
    else:
        step = np.sign(slope) * (high - low) / 4
    new = float(min(max(theta + step, low + (high - low) * 1e-3), high))
    return None if abs(new - theta) < 1e-9 else new


class TransferLearner(PartBasedLearner):
    """Algorithm 6 over a database of known objects (any iterable of ``KnownObject``).

    Parameters beyond ``PartBasedLearner``'s: ``database``; ``consistency_tol`` (m), how far
    an observed displacement may lie from the source's prediction and still be consistent;
    ``n_neighbors``, ``max_distance``, ``weights`` of the part similarity (Algorithm 5);
    ``stop_at_goal``, whether line 31's Algorithm 4 stops once an action reached the goal;
    ``other_parts``, whether to go on past the look-alike of the source's functional part
    (lines 24-31: one try per action on the other look-alike parts, then Algorithm 4 on the
    novel ones). False stops after line 23 and leaves those parts to the caller: an agent
    that learns them a pair at a time, in its own order (issue 32). ``first_pair``, a
    (part, action) pair that lines 17-23 check before the other actions when they work on
    its part (Algorithm 6 leaves their order open; None: the order of the action types):
    the pair an agent asked about, the one its random learning would have tried first, so
    that transfer never tries it later than random learning would (issue 32: a lid sliding
    right after o1 took 5 or 6 exploratory actions where random learning, drawing the
    sweep first, took 4).

    After ``fit(obj)``, besides PartBasedLearner's attributes: ``candidates_`` (Algorithm 5's
    ranking), ``source_`` (the source's name or None), ``similar_parts_`` (Ψ_sim) and
    ``branch_``. ``functional_`` is the pair of the first action that reached the goal.
    """

    _parameter_constraints: ClassVar[dict[str, list]] = {
        **PartBasedLearner._parameter_constraints,
        "database": "no_validation",  # any iterable of KnownObject: checked in fit
        "consistency_tol": [POSITIVE], "n_neighbors": [POSITIVE_INT], "stop_at_goal": ["boolean"],
        "other_parts": ["boolean"], "first_pair": [tuple, None],
        "max_distance": [POSITIVE, None], "weights": ["array-like", None],
    }

    def __init__(self, database: Iterable[KnownObject] = (), n: int = 5, n_min: int = 3,
                 settle_tol: float = 1e-4, min_displacement: float = 0.01, goal: float = 0.1,
                 delta1: float = 0.03, delta2: float = 0.002, max_checks: int = 3,
                 consistency_tol: float = 0.01, n_neighbors: int = 3,
                 max_distance: float = 1.0, weights: Sequence[float] = DEFAULT_WEIGHTS,
                 aim: str = "goal_plus_delta1", stop_at_goal: bool = True,
                 other_parts: bool = True, first_pair: tuple[str, str] | None = None,
                 random_state: int | np.random.RandomState | None = None) -> None:
        super().__init__(n=n, n_min=n_min, settle_tol=settle_tol,
                         min_displacement=min_displacement, goal=goal, delta1=delta1,
                         delta2=delta2, max_checks=max_checks, aim=aim,
                         random_state=random_state)
        self.stop_at_goal = stop_at_goal
        self.other_parts = other_parts
        self.first_pair = first_pair
        self.database = database
        self.consistency_tol = consistency_tol
        self.n_neighbors = n_neighbors
        self.max_distance = max_distance
        self.weights = weights

    def fit(self, obj: object) -> TransferLearner:
        """Run Algorithm 5 and then Algorithm 6 (or Algorithm 4 without a source) on ``obj``."""
        session = self._start(obj)  # type: ignore[arg-type]
        known = list(self.database)
        if not all(isinstance(k, KnownObject) for k in known):
            raise ValueError("database must hold KnownObject entries")
        similarity_params = {"n_neighbors": self.n_neighbors, "max_distance": self.max_distance,
                             "weights": self.weights}
        self.candidates_ = rank_sources(known, session.view, session.params.goal,
                                        delta2=session.params.delta2,
                                        similarity_params=similarity_params)
        self.similar_parts_: list[str] = []
        if not self.candidates_:
            self.source_ = None
            for part in session.view.parts:
                for action in session.bounds:
                    session.explore_pair(part, action, stop_at_goal=False)
            found = session.exploit(checks=session.params.max_checks)
            self.branch_ = "no_source" if found else "failed"
            self._finish(session, found)
            return self
        source = self.candidates_[0]
        self.source_ = source.known.name
        similarity = fit_similarity(known, **similarity_params)
        assert similarity is not None  # a candidate implies known parts
        self.branch_ = self._transfer(session, source, similarity)
        self._finish(session, session.success)
        return self

    def _transfer(self, session: Session, source: SourceCandidate,
                  similarity: PartSimilarity) -> str:
        """Lines 2-31 of Algorithm 6; returns the branch that reached the goal."""
        known, rehearsal = source.known, source.rehearsal
        part, action = source.target_part, rehearsal.action
        self.similar_parts_.append(part)
        if self._exploit_source(session, known, rehearsal, part):
            return "direct" if len(session.trials) == 1 else "gradient"
        others = sorted((a for a in session.bounds if a != action),
                        key=lambda a: (part, a) != self.first_pair)  # stable: the rest in order
        if self._check_consistency(session, known, rehearsal.part, part, others):
            return "other_action"
        if not self.other_parts:
            return "failed"
        for source_part in known.parts:
            if source_part == rehearsal.part:
                continue
            target = similar_part(similarity, session.view, source_part,
                                  known.parts[source_part], exclude=self.similar_parts_)
            if target is None:
                continue
            self.similar_parts_.append(target)
            if self._check_consistency(session, known, source_part, target,
                                       list(session.bounds)):
                return "other_part"
        for left in session.view.parts:  # line 31: Algorithm 4 on the novel-looking parts
            if left in self.similar_parts_:
                continue
            for other in session.bounds:
                session.explore_pair(left, other, stop_at_goal=self.stop_at_goal)
                if session.reached and self.stop_at_goal:
                    return "fallback"
        found = session.exploit(checks=session.params.max_checks)  # Algorithm 4, lines 11-12
        return "fallback" if found or session.reached else "failed"

    def _exploit_source(self, session: Session, known: KnownObject, rehearsal: Selection,
                        part: str) -> bool:
        """Lines 7-16: the source's θ*, then steps along its gradient, then the own model."""
        action = rehearsal.action
        model = known.models[rehearsal.pair]
        bounds = session.bounds[action]
        theta = rehearsal.theta if rehearsal.theta is not None else bounds[1]
        for k in range(1, session.params.n + 1):
            trial = session.act(part, action, theta, "transfer" if k == 1 else "gradient")
            if trial.reached:
                return True
            if session.dead((part, action)):
                break
            step = gradient_step(theta, model, trial.state_after, session.params.goal, bounds)
            if step is None:
                break
            theta = step
        return session.exploit([(part, action)], only_if_predicted=True) is not None

    def _check_consistency(self, session: Session, known: KnownObject, source_part: str,
                           part: str, actions: Sequence[str]) -> bool:
        """Lines 17-23 (and 27-29): one try per action type; follow up the inconsistent ones."""
        p = session.params
        for action in actions:
            if (part, action) in session.models:
                continue
            theta = session.bounds[action][1]
            trial = session.act(part, action, theta, "consistency")
            if trial.reached:
                return True
            model = known.models.get((source_part, action))
            predicted = 0.0 if model is None else float(model.predict_displacement(theta)[0])
            moved = abs(trial.part_displacement) >= p.min_displacement
            if moved and abs(trial.part_displacement - predicted) > self.consistency_tol:
                session.explore_pair(part, action, stop_at_goal=True)
                if session.reached:
                    return True
                if session.exploit([(part, action)], only_if_predicted=True) is not None:
                    return True
        return False
