"""The ``learn`` behaviour (thesis §6.3.4): explore an action on a part, report an affordance.

Random mode samples θ uniformly in the action's bounds lo < θ <= hi (thesis: 0 < θ <= θ0),
measures each effect (the change of opening, eq. 5.3) through a plain callable, fits
Ĥ(θ) = b + c·θ (eq. 6.7) after every sample and stops when the regression has settled
(eq. 5.19) or after ``n_max`` samples. The model's maximum e_max (eq. 6.8) decides the evidence:
``afford(Obj, Act, Eff, 0, 0, r1)`` when e_max ≥ δ (6.10, 6.11), else
``afford(Obj, Act, Eff, 0, 0, r2)`` (6.14). θ_max (eq. 6.13) is what the agent uses to verify
the prediction; ``verify_effect`` turns the observed effect into ``afford(..., 1, 1, 1)``
or ``afford(..., 1, 0, 0)`` (§6.3.3).

Active mode (chapter 4) explores θ with Algorithm 3 instead: a forward model F(s, θ) learns
the effect while CACLA chooses the next θ, the loop stops when the averaged TD error settles
(eq. 4.10) or after ``active_n_max`` tries, and e_max, θ_max are read off F (6.8, 6.13); the
verdict is then the same r1/r2 evidence (``behaviours.learners.theta_exploration``).

Results are plain Python data (``AffordanceEvidence``): turning them into an agent's percepts
is the robot application's job (``robot/envs/garbage.py``), so this layer knows no agent.
``learn`` knows nothing of agents or MuJoCo: it explores any ``effect(θ) -> float``.
``learn_in_world`` runs it on the simulated can through ``behaviours.skills.perform_skill``,
and ``AffordanceBehaviours`` carries out an agent's ``learn`` and ``apply`` requests.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from sklearn.base import BaseEstimator
from sklearn.utils import check_random_state

from behaviours.learners.effect_models import LinearEffectModel, ModelStore, check_bounds
from behaviours.learners.theta_exploration import explore_theta

if TYPE_CHECKING:
    from behaviours.perception import Perception
    from sim.world import GarbageWorld

LEARNING_MODES = ("random", "active", "transfer")
_LATER_MODES = {
    "transfer": "is the whole-object behaviour behaviours.part_learning.learn_by_transfer "
                "(Algorithm 6), not an exploration of one pair's Ĥ",
}
ACTIVE_N_MAX = 100
"""N_s of Algorithm 3 for one action parameter (thesis §4.6.1: 100 steps for 1-D actions)."""
EffectFn = Callable[[float], float]


class LearningModeUnavailable(NotImplementedError):
    """A learning mode the language names but this version does not implement yet."""


class RandomExplorer(BaseEstimator):
    """Random exploration of θ in lo < θ <= hi until Ĥ settles (eq. 5.19) or n_max samples.

    Eq. 5.19 is checked from the ``n_min``-th sample on. Three samples that happen to lie close
    together can look settled; on the five simulated cans (functional pair, 10 seeds each)
    n_min = 3 missed one effective action in 50 and n_min = 4 none, so 4 is the default.
    """

    def __init__(
        self,
        bounds: tuple[float, float] = (0.0, 0.1),
        n_max: int = 10,
        n_min: int = 4,
        settle_tol: float = 1e-4,
        random_state: int | np.random.RandomState | None = None,
    ) -> None:
        self.bounds = bounds
        self.n_max = n_max
        self.n_min = n_min
        self.settle_tol = settle_tol
        self.random_state = random_state

    def explore(self, effect_fn: EffectFn) -> LinearEffectModel:
        """Sample θ, call effect_fn(θ), refit; sets model_, n_samples_ and settled_."""
        low, high = check_bounds(self.bounds)
        if not isinstance(self.n_max, int) or self.n_max < 1:
            raise ValueError(f"n_max must be a positive whole number, got {self.n_max!r}")
        if not isinstance(self.n_min, int) or self.n_min < 2:
            raise ValueError(f"n_min must be a whole number of at least 2, got {self.n_min!r}")
        if not (isinstance(self.settle_tol, (int, float)) and self.settle_tol > 0):
            raise ValueError(f"settle_tol must be a positive number, got {self.settle_tol!r}")
        rng = check_random_state(self.random_state)
        model = LinearEffectModel()
        self.settled_ = False
        for k in range(1, self.n_max + 1):
            theta = high - float(rng.uniform(0.0, high - low))  # lo < θ <= hi
            effect = effect_fn(theta)
            if not isinstance(effect, numbers.Real) or not math.isfinite(effect):
                raise ValueError(
                    f"the effect function returned {effect!r} for theta={theta:.4f}; "
                    "it must return a finite number (the change of opening in metres)"
                )
            model.partial_fit([theta], [float(effect)])
            self.n_samples_ = k
            if k >= self.n_min and model.settled(self.settle_tol):
                self.settled_ = True
                break
        self.model_ = model
        return model


@dataclass(frozen=True)
class AffordanceEvidence:
    """The six arguments of an ``afford(Obj, Act, Eff, Tot, Suc, Rel)`` percept (eq. 6.1).

    Numbers keep their Python type (``1`` stays an int, ``0.3`` a float) so the percept the
    environment builds from them is exactly the term the agent's rules expect.
    """

    obj: str
    act: str
    eff: str
    tot: int
    suc: int
    rel: int | float


@dataclass(frozen=True)
class LearnResult:
    """What ``learn`` reports: the evidence, the best parameter and its predicted effect."""

    evidence: AffordanceEvidence  # afford(Obj, Act, Eff, 0, 0, r1 | r2)
    theta_max: float  # eq. 6.13
    e_max: float  # eq. 6.8
    samples: int  # how many actions the exploration performed
    settled: bool  # whether eq. 5.19 (random) or 4.10 (active) stopped it, else the limit
    model: LinearEffectModel


def verify_effect(
    *, obj: str, action: str, effect_name: str, observed_effect: float, delta: float
) -> AffordanceEvidence:
    """§6.3.3: afford(..., 1, 1, 1) if the observed effect reaches δ (6.9), else (..., 1, 0, 0)."""
    if observed_effect >= delta:
        return AffordanceEvidence(obj, action, effect_name, 1, 1, 1)
    return AffordanceEvidence(obj, action, effect_name, 1, 0, 0)


def _check_mode(mode: str) -> None:
    """Accept "random" and "active"; refuse later modes and unknown names with a clear error."""
    if mode in _LATER_MODES:
        raise LearningModeUnavailable(
            f"learning mode {mode!r} {_LATER_MODES[mode]}; the modes available now are "
            "'random' and 'active'"
        )
    if mode not in LEARNING_MODES:
        modes = ", ".join(LEARNING_MODES)
        raise ValueError(f"unknown learning mode {mode!r}; the modes are {modes}")


def _check_name(value: object, what: str) -> str:
    """A non-empty string naming an atom, or a clear error."""
    if not isinstance(value, str) or not value:
        raise ValueError(f"{what} must be a non-empty name, got {value!r}")
    return value


def learn(
    effect_fn: EffectFn,
    *,
    obj: str,
    action: str,
    effect_name: str,
    mode: str = "random",
    bounds: tuple[float, float],
    delta: float,
    n_max: int,
    random_state: int | np.random.RandomState | None,
    store: ModelStore | None = None,
    key: Sequence[str] | None = None,
    n_min: int = 4,
    settle_tol: float = 1e-4,
    r1: float = 0.3,
    r2: float = 0.05,
    active_n_max: int = ACTIVE_N_MAX,
    start_state: float = 0.0,
) -> LearnResult:
    """Learn Ĥ for (obj, action) in ``mode`` and report the affordance evidence (§6.3.4).

    ``random``: uniform θ, Ĥ a line refitted after every sample until it settles or ``n_max``.
    ``active``: Algorithm 3 from ``start_state`` (the opening every try starts from) for at
    most ``active_n_max`` tries; e_max and θ_max come from its forward model (6.8, 6.13), and
    the line fitted to the same samples is what the store keeps. ``key`` names the model in
    ``store`` (normally (can, part, action); default (obj, action)); a stored model under the
    same key is replaced by the new one and the store is saved.
    """
    _check_mode(mode)
    for value, what in ((obj, "obj"), (action, "action"), (effect_name, "effect_name")):
        _check_name(value, what)
    if not (isinstance(delta, (int, float)) and math.isfinite(delta)):
        raise ValueError(f"delta must be a finite number (metres), got {delta!r}")
    if not (isinstance(r1, (int, float)) and isinstance(r2, (int, float)) and 0 < r2 < r1 < 1):
        raise ValueError(f"reliabilities must satisfy 0 < r2 < r1 < 1, got r1={r1!r} r2={r2!r}")
    if mode == "active":
        outcome = explore_theta(effect_fn, bounds=check_bounds(bounds), state=start_state,
                                n_max=active_n_max, random_state=random_state)
        model = LinearEffectModel().fit(outcome.thetas, outcome.effects)
        theta_max, e_max = outcome.theta_max, outcome.e_max
        samples, settled = outcome.samples, outcome.converged
    else:
        explorer = RandomExplorer(
            bounds=bounds,
            n_max=n_max,
            n_min=n_min,
            settle_tol=settle_tol,
            random_state=random_state,
        )
        model = explorer.explore(effect_fn)
        theta_max, e_max = model.maximum(explorer.bounds)
        samples, settled = explorer.n_samples_, explorer.settled_
    reliability = r1 if e_max >= delta else r2
    if store is not None:
        store.put(tuple(key) if key is not None else (obj, action), check_bounds(bounds), model)
    return LearnResult(
        evidence=AffordanceEvidence(obj, action, effect_name, 0, 0, reliability),
        theta_max=theta_max,
        e_max=e_max,
        samples=samples,
        settled=settled,
        model=model,
    )


def _measured_effect(
    world: GarbageWorld, perception: Perception | None, action: str, part: str, theta: float
) -> float:
    """Perform action(part, θ); the change of opening (eq. 5.3), by truth or by perception."""
    from behaviours.skills import perform_skill

    if perception is None:
        return perform_skill(world, action, part, theta).effect
    before = perception.observe(world).opening
    perform_skill(world, action, part, theta)
    return perception.observe(world).opening - before


def learn_in_world(
    world: GarbageWorld,
    *,
    part: str,
    action: str,
    effect_name: str = "opened",
    mode: str = "random",
    delta: float,
    n_max: int,
    random_state: int | np.random.RandomState | None,
    store: ModelStore | None = None,
    perception: Perception | None = None,
    **options: float,
) -> LearnResult:
    """``learn`` on the simulated can: θ in the action's THETA_BOUNDS, key (can, part, action).

    Like the thesis's exploration (§5.6.1: every try starts from the same object state), each
    exploratory action starts from the opening the can had when learning began, and the can is
    put back to that opening afterwards, so the agent's next action meets the can as it left it.
    The effect is the change of opening (eq. 5.3) from ground truth, or as ``perception`` sees
    it (e.g. the camera, eq. 5.14) when one is given. ``options`` go to ``learn`` (n_min,
    settle_tol, r1, r2).
    """
    from behaviours.skills import THETA_BOUNDS, check_skill

    _check_mode(mode)
    check_skill(world, action, part, THETA_BOUNDS.get(action, (0.0, 0.0))[1])
    start = world.opening()
    seen = perception.observe(world).opening if perception is not None else start

    def effect(theta: float) -> float:
        world.set_opening(start)
        return _measured_effect(world, perception, action, part, theta)

    try:
        return learn(
            effect,
            obj=part,
            action=action,
            effect_name=effect_name,
            mode=mode,
            bounds=THETA_BOUNDS[action],
            delta=delta,
            n_max=n_max,
            random_state=random_state,
            store=store,
            key=(world.can, part, action),
            start_state=seen,
            **options,
        )
    finally:
        world.set_opening(start)


@dataclass(frozen=True)
class ApplyResult:
    """What using an affordance reports: the verification evidence, the θ used, the effect."""

    evidence: AffordanceEvidence  # afford(Obj, Act, Eff, 1, 1, 1) or (Obj, Act, Eff, 1, 0, 0)
    theta: float
    effect: float


class AffordanceBehaviours:
    """The affordance actions an agent sends to the simulated can: learn and apply (§6.3).

    ``learn(part, action)`` explores (§6.3.4) and reports the r1/r2 evidence; ``apply(part,
    action)`` acts once with the best known θ (eq. 6.13) and reports the verification evidence
    (§6.3.3). One seeded generator feeds every exploration, so a whole run is reproducible.
    """

    def __init__(
        self,
        world: GarbageWorld,
        *,
        delta: float = 0.1,
        n_max: int = 10,
        seed: int = 0,
        store: ModelStore | None = None,
        perception: Perception | None = None,
        **options: float,
    ) -> None:
        self.world = world
        self.delta = delta
        self.n_max = n_max
        self.store = store
        self.perception = perception
        self.options = options
        self._rng = np.random.RandomState(seed)
        self._theta: dict[tuple[str, str, str], float] = {}

    def learn(
        self, part: str, action: str, effect_name: str = "opened", mode: str = "random"
    ) -> LearnResult:
        """Explore action on part; remember θ_max for this can."""
        result = learn_in_world(
            self.world,
            part=part,
            action=action,
            effect_name=effect_name,
            mode=mode,
            delta=self.delta,
            n_max=self.n_max,
            random_state=self._rng,
            store=self.store,
            perception=self.perception,
            **self.options,
        )
        self._theta[(self.world.can, part, action)] = result.theta_max
        return result

    def remember(self, part: str, action: str, theta: float) -> None:
        """Use θ for (part, action) on this can from now on (e.g. what transfer found)."""
        self._theta[(self.world.can, part, action)] = theta

    def theta_for(self, part: str, action: str) -> float:
        """θ_max learned on this can in this run, else from the store, else the largest θ.

        The store may answer with another can's model of the part (``ModelStore.lookup``).
        """
        from behaviours.skills import THETA_BOUNDS

        known = self._theta.get((self.world.can, part, action))
        if known is not None:
            return known
        stored = self.store.lookup(self.world.can, part, action) if self.store else None
        if stored is not None:
            return stored.model.maximum(stored.bounds)[0]
        return THETA_BOUNDS[action][1]

    def apply(self, part: str, action: str, effect_name: str = "opened") -> ApplyResult:
        """Act once with theta_for(part, action) and verify the effect against δ (6.9)."""
        from behaviours.skills import THETA_BOUNDS, check_skill

        check_skill(self.world, action, part, THETA_BOUNDS.get(action, (0.0, 0.0))[1])
        theta = self.theta_for(part, action)
        effect = _measured_effect(self.world, self.perception, action, part, theta)
        evidence = verify_effect(
            obj=part,
            action=action,
            effect_name=effect_name,
            observed_effect=effect,
            delta=self.delta,
        )
        return ApplyResult(evidence=evidence, theta=theta, effect=effect)
