"""Goal generation and skill acquisition with a learned forward model (thesis §4.5).

In state s the robot rehearses internally: it predicts F(s, a) for a set A_M of M actions
evenly spread over the action space and takes the largest predicted effect as its goal
e_g (4.12) and the action achieving it as a* (4.13). It performs a*, observes the effect
e = s' − s and records SK* = {s, a*, e} (4.14), until |e| < τ (4.15). Then it does the same
minimising (4.16, 4.17), recording SK_* (4.18): paired skills, e.g. open and close a lid.
Works on any ``ContinuousWorld`` with a one-dimensional state.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from sklearn.utils._param_validation import validate_params

from behaviours.learners.exploration import ContinuousWorld
from behaviours.learners.forward_model import ForwardModel
from behaviours.learners.validation import POSITIVE, POSITIVE_INT, ActionBounds, as_rows

__all__ = ["SkillSequence", "SkillStep", "acquire_skills", "candidate_actions", "goal_action"]

PHASES = ("maximise", "minimise")


@dataclass(frozen=True)
class SkillStep:
    """One element of SK* or SK_*: the state, the action, the goal e_g and the effect e."""

    state: float
    action: tuple[float, ...]
    goal: float
    effect: float


@dataclass(frozen=True)
class SkillSequence:
    """The steps of one phase and whether it ended on |e| < τ (else on ``max_steps``)."""

    phase: str  # "maximise" (SK*, e.g. open) or "minimise" (SK_*, e.g. close)
    steps: tuple[SkillStep, ...]
    terminated: bool


@validate_params({"bounds": [ActionBounds], "n_grid": [POSITIVE_INT], "endpoint": ["boolean"]},
                 prefer_skip_nested_validation=True)
def candidate_actions(bounds: ActionBounds, n_grid: int = 11,
                      endpoint: bool = True) -> np.ndarray:
    """A_M: an even grid of ``n_grid`` values per dimension over the bounds (M = n_grid^d),
    from the lower bound to the upper one, or (``endpoint=False``) stopping one step short of
    it (10 points over [-0.01, 0.01] m give -0.010, -0.008, ..., 0.008)."""
    n = int(n_grid)
    axes = [np.linspace(lo, hi, n, endpoint=bool(endpoint))
            for lo, hi in zip(bounds.low, bounds.high, strict=True)]
    return np.stack([g.ravel() for g in np.meshgrid(*axes, indexing="ij")], axis=1)


def goal_action(
    model: ForwardModel, state: float, candidates: np.ndarray, maximise: bool = True
) -> tuple[np.ndarray, float]:
    """(a*, e_g) by eq. 4.12–4.13 (``maximise``) or (a_*, e_g) by eq. 4.16–4.17."""
    predicted = np.asarray(model.predict_effects([state], candidates), dtype=float)
    if predicted.ndim != 1:
        raise ValueError("goal generation needs a forward model of a one-dimensional effect")
    best = int(np.argmax(predicted) if maximise else np.argmin(predicted))
    return candidates[best].copy(), float(predicted[best])


@validate_params({"model": [ForwardModel], "world": "no_validation", "n_grid": [POSITIVE_INT],
                  "tau": [POSITIVE], "max_steps": [POSITIVE_INT], "endpoint": ["boolean"]},
                 prefer_skip_nested_validation=True)
def acquire_skills(
    model: ForwardModel,
    world: ContinuousWorld,
    *,
    n_grid: int = 11,
    tau: float = 0.01,
    max_steps: int = 30,
    endpoint: bool = True,
) -> tuple[SkillSequence, SkillSequence]:
    """Run both phases on ``world`` from its current state: (SK*, SK_*), choosing among
    ``candidate_actions(bounds, n_grid, endpoint)``."""
    bounds = ActionBounds(world.action_bounds)
    tau, limit = float(tau), int(max_steps)
    candidates = candidate_actions(bounds, n_grid, endpoint)
    sequences = []
    for phase in PHASES:
        steps: list[SkillStep] = []
        terminated = False
        for _ in range(limit):
            state = _scalar_state(world.observe())
            action, goal = goal_action(model, state, candidates, maximise=phase == "maximise")
            next_state = _scalar_state(world.step(action.copy()))
            effect = next_state - state  # 4.20
            steps.append(SkillStep(state, tuple(float(x) for x in action), goal, effect))
            if abs(effect) < tau:  # 4.15
                terminated = True
                break
        sequences.append(SkillSequence(phase, tuple(steps), terminated))
    return sequences[0], sequences[1]


def _scalar_state(value: object) -> float:
    """A world's one-dimensional state as a finite float."""
    row = as_rows(np.atleast_1d(np.asarray(value, dtype=float))[None, :], "the world's state")
    if row.shape[1] != 1:
        raise ValueError(f"skill acquisition needs a one-dimensional state, got {row.shape[1]}")
    return float(row[0, 0])
