"""What the chapter-4 studies share: the four configurations, Algorithm 3's parameters as a
config, and one exploration run.

A configuration is a can and the part the hand holds (thesis §4.6: the push-lid can, our o1,
and the pull-handle can, our o5) with 1-D (Δx) or 3-D (Δx, Δy, Δz) actions and its budget N_s
(100 for 1-D, 300 for 3-D). ``explore`` runs Algorithm 3 or the random baseline on a fresh
world through ``behaviours.contact.PartContact``; the same seed gives both methods the same
first random actions.
"""

from __future__ import annotations

import math
import statistics
from dataclasses import dataclass
from typing import Annotated, Literal

import numpy as np
from pydantic import Field

from robot.reproduce.framework import Deviation, Reading, ScaledConfig, SeedResult

CONFIGURATIONS = ("lid-1d", "lid-3d", "handle-1d", "handle-3d")
METHODS = ("active", "random")
Perception = Literal["truth", "camera"]
Positive = Annotated[float, Field(gt=0.0)]
Rate = Annotated[float, Field(gt=0.0, le=1.0)]


@dataclass(frozen=True)
class Configuration:
    """One of Figs 4.6–4.9: which can, which part, how many action dimensions."""

    name: str
    can: str
    part: str
    dims: int


SETUPS = {
    "lid-1d": Configuration("lid-1d", "o1", "lid", 1),
    "lid-3d": Configuration("lid-3d", "o1", "lid", 3),
    "handle-1d": Configuration("handle-1d", "o5", "handle", 1),
    "handle-3d": Configuration("handle-3d", "o5", "handle", 3),
}


class ExplorationConfig(ScaledConfig):
    """Algorithm 3's parameters (§4.6.1) and where s_o comes from."""

    perception: Perception = "truth"
    """Where s_o (eq. 4.19) comes from: the simulator's ground truth or the rendered frames
    of the close camera (OpenCV)."""
    n_random: Annotated[int, Field(ge=0)] = 20
    """The first actions drawn at random in both methods (§4.6.1: N = 20)."""
    window: Annotated[int, Field(ge=1)] = 20
    """N of the averaged TD error δ̄ (eq. 4.11)."""
    tolerance: Positive = 1e-4
    """ε of the convergence test (eq. 4.10)."""
    budget_1d: Annotated[int, Field(ge=1)] = 100
    """N_s with 1-D actions (§4.6.1; scaled, never below n_random + 2)."""
    budget_3d: Annotated[int, Field(ge=1)] = 300
    """N_s with 3-D actions (§4.6.1; scaled, never below n_random + 2)."""
    sigma: Positive = 0.2
    """Exploration noise σ per unit action dimension (CACLA's Gaussian, §4.6.1)."""
    gamma: Rate = 0.9
    """Discount factor γ of the TD error (eq. 4.8)."""
    alpha: Rate = 0.3
    """Learning rate α of the critic (§4.6.1)."""
    zeta: Rate = 0.3
    """Learning rate ζ of the actor (§4.6.1)."""
    beta: Rate = 0.3
    """Learning rate β of the forward model (§4.6.1)."""
    n_hidden: Annotated[int, Field(ge=1)] = 10
    """Hidden tanh units of each network (§4.6.1)."""

    def budget(self, setup: Configuration) -> int:
        """N_s of ``setup`` shrunk by ``scale``, never below N + 2 (the least that lets (4.10)
        be tested)."""
        full = self.budget_1d if setup.dims == 1 else self.budget_3d
        return max(self.n_random + 2, round(full * self.scale))


class ScaledExplorationConfig(ExplorationConfig):
    """Algorithm 3's parameters and the unit s_o is measured in, which (4.10)'s ε is read
    against."""

    state_scale: Annotated[float, Field(gt=0.0), Reading(
        "eq. 4.19: s_o = w×h / (W×H), a share of the image, 0 ≤ s_o ≤ 1; §4.6.1: \"The TD "
        "errors were averaged over N = 20 actions in equation (4.10) and ε = 1 × 10⁻⁴\", "
        "without saying in which unit of s_o (and so of e_o, r = |η| and δ) ε was meant; "
        "Figs 4.4–4.5 plot the state as 0–0.2.")] = 1.0
    """s_o as Algorithm 3 sees it: eq. 4.19's share times this factor (100: a percentage of
    the image). Effects, rewards, TD errors and the averages (4.10) compares scale with it;
    the recorded states and effects are divided back, so their metrics stay in eq. 4.19's
    share."""


class ScaledState:
    """A ``ContinuousWorld`` whose state is another's times ``factor`` (s_o in another unit)."""

    def __init__(self, world: object, factor: float) -> None:
        self.world, self.factor = world, float(factor)

    @property
    def action_bounds(self) -> object:
        return self.world.action_bounds  # type: ignore[attr-defined]

    def observe(self) -> np.ndarray:
        """The wrapped world's state, scaled."""
        return np.asarray(self.world.observe(), dtype=float) * self.factor  # type: ignore

    def step(self, action: np.ndarray) -> np.ndarray:
        """Act on the wrapped world; its next state, scaled."""
        return np.asarray(self.world.step(action), dtype=float) * self.factor  # type: ignore


def explore(setup: Configuration, method: str, seed: int, config: ExplorationConfig,
            stop: bool, state_scale: float = 1.0):
    """One exploration of ``setup`` by ``method`` on a fresh world, its state seen times
    ``state_scale``: the fitted ActiveExplorer and the contact (the caller closes its
    world)."""
    from behaviours.contact import CONTACT_CAMERA, PartContact
    from behaviours.learners.exploration import ActiveExplorer
    from behaviours.perception import make_perception
    from sim.world import GarbageWorld

    world = GarbageWorld(setup.can, seed=seed)
    contact = PartContact(world, setup.part, dims=setup.dims,
                          perception=make_perception(config.perception, CONTACT_CAMERA))
    contact.start()
    explorer = ActiveExplorer(
        mode=method, n_max=config.budget(setup), n_random=config.n_random,
        window=config.window, tol=config.tolerance, sigma=config.sigma, gamma=config.gamma,
        alpha=config.alpha, zeta=config.zeta, beta=config.beta, n_hidden=config.n_hidden,
        random_state=seed, stop=stop).explore(
            contact if state_scale == 1.0 else ScaledState(contact, state_scale))
    return explorer, contact


CH4_DEVIATIONS = (
    Deviation("Cans and arm", "the NAO's left arm on two real cans, 10-12 cm away (§4.6.1).",
              "a MuJoCo hand that holds o1's lid (sliding over its face) or grips o5's handle; "
              "its reach ends a few centimetres from the hold, so about six steps open or close "
              "the part fully and then the state stays put."),
    Deviation("Camera", "NAO's bottom camera, W × H = 320 × 240 (§4.6.1).", "a `close` camera "
              "on the head camera's line of sight at 0.6 of its distance, where a fully open "
              "can fills about 0.12-0.13 of the image (thesis: up to 0.114-0.135)."),
)
"""What chapter 4's studies run on instead of the NAO (no parameter decides it)."""


def rounded(values: np.ndarray, digits: int = 6) -> list:
    """A float array as JSON lists, NaN as None."""
    return [None if isinstance(v, float) and math.isnan(v) else v
            for v in np.round(np.asarray(values, dtype=float), digits).tolist()]


def median_or_none(values: list[int]) -> float | None:
    """The median of the values, None when there are none."""
    return float(statistics.median(values)) if values else None


class ExplorationRun(SeedResult):
    """One exploration of one configuration by one method, over the whole budget N_s."""

    converged_at: int | None
    """The first step at which (4.10) held: where Algorithm 3 stops."""
    steps: int
    averaged: list[float | None]
    """δ̄ of eq. 4.11 at each step (None before N steps)."""
    td_errors: list[float | None]
    states: list[float | None]
    effects: list[float | None]
    actions: list[list[float | None]]
    surface: list[list[float | None]] | None = None
    """1-D only: the learned F over the action grid at each state slice (Figs 4.4–4.5)."""


class Exploration(SeedResult):
    """Every configuration and method of one seed."""

    perception: str
    configurations: dict[str, dict[str, ExplorationRun]]

    def of(self, name: str, method: str) -> ExplorationRun:
        return self.configurations[name][method]
