"""Active exploration of one action type's parameter θ (thesis §6.3.4 with chapter 4's learner).

Chapter 6's ``learn(Obj, Act, Eff, mode)`` explores the continuous parameter θ of one action
type, lo < θ ≤ hi, every try starting from the same object state. In ``active`` mode that
exploration is Algorithm 3: the forward model F(s, θ) learns the effect, CACLA chooses the next
θ, and the loop stops on (4.10) or after ``n_max`` tries. The verdict then comes from the
forward model instead of a line: e_max = max_θ F(s, θ) (6.8) and θ_max its argmax (6.13),
taken over an even grid of θ in (lo, hi].
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from behaviours.learners.exploration import ActiveExplorer
from behaviours.learners.forward_model import ForwardModel
from behaviours.learners.validation import ActionBounds

__all__ = ["ThetaExploration", "ThetaWorld", "explore_theta"]

OPEN_END = 1e-3
"""The learner's θ range starts this share of (hi − lo) above lo: lo itself is no action."""
GRID = 101
"""Points of the θ grid over which e_max and θ_max are read off the forward model."""


class ThetaWorld:
    """A ``ContinuousWorld`` over ``effect(θ)``: every try starts from the same state s."""

    def __init__(self, effect: Callable[[float], float], bounds: tuple[float, float],
                 state: float) -> None:
        """``bounds`` is (lo, hi) with lo < θ ≤ hi; ``state`` is s (e.g. the opening now)."""
        low, high = ActionBounds([bounds]).as_list()[0]
        self.action_bounds = [(low + OPEN_END * (high - low), high)]
        self.effect = effect
        self.state = float(state)
        if not np.isfinite(self.state):
            raise ValueError(f"the start state must be a finite number, got {state!r}")

    def observe(self) -> float:
        """s: the state every try starts from."""
        return self.state

    def step(self, action: np.ndarray) -> float:
        """Try θ = action[0]; the state right after it is s + effect(θ)."""
        effect = self.effect(float(action[0]))
        if isinstance(effect, bool) or not isinstance(effect, (int, float, np.floating)) or (
                not np.isfinite(effect)):
            raise ValueError(f"the effect function returned {effect!r} for theta="
                             f"{float(action[0]):.4f}; it must return a finite number")
        return self.state + float(effect)


@dataclass(frozen=True)
class ThetaExploration:
    """The outcome: θ_max and e_max from F, the tries made, whether (4.10) stopped them."""

    theta_max: float  # eq. 6.13
    e_max: float  # eq. 6.8
    thetas: np.ndarray  # every θ tried, in order
    effects: np.ndarray  # the effect each try measured
    converged: bool  # (4.10) held (else n_max stopped the loop)
    forward_model: ForwardModel

    @property
    def samples(self) -> int:
        """How many exploratory actions were performed."""
        return int(self.thetas.size)


def explore_theta(
    effect: Callable[[float], float],
    *,
    bounds: tuple[float, float],
    state: float,
    n_max: int = 100,
    n_random: int = 20,
    random_state: int | np.random.RandomState | None = None,
) -> ThetaExploration:
    """Algorithm 3 over θ from ``state`` (thesis defaults otherwise); verdict from F."""
    world = ThetaWorld(effect, bounds, state)
    explorer = ActiveExplorer(mode="active", n_max=n_max, n_random=n_random,
                              random_state=random_state).explore(world)
    low, high = world.action_bounds[0]
    grid = np.linspace(low, high, GRID)
    predicted = explorer.forward_model_.predict_effects([world.state], grid[:, None])
    best = int(np.argmax(predicted))
    history = explorer.history_
    return ThetaExploration(
        theta_max=float(grid[best]),
        e_max=float(predicted[best]),
        thetas=history.actions[:, 0].copy(),
        effects=history.effects[:, 0].copy(),
        converged=explorer.converged_,
        forward_model=explorer.forward_model_,
    )
