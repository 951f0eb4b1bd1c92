"""The simulated can as an object under test for the chapter-5 learners (behaviours/learners).

``CanUnderTest`` wraps a ``GarbageWorld`` and a perception (camera or truth): ``perceive``
gives the parts' Table 5.1 descriptors, ``above`` relations and the opening s_o (eq. 5.14);
``perform(part, action, θ)`` puts the can back in the state it had when learning began (the
thesis's lid is closed before every try, §5.6.1), runs the motor skill and measures the part's
displacement (eq. 5.15) and the opening before and after, as the perception sees them. It
counts every action it performs.

``learn_by_transfer`` is the ``learn(..., transfer)`` behaviour: Algorithm 6 on the can against
the known-object database, with afford/model evidence for every pair it tried, after which the
can joins the database. When no known object is relevant (Algorithm 5 finds no source), the
transfer would be Algorithm 4 on every part and action; an agent that asks about one pair gets
``PairEpisode`` instead: Algorithm 4 one pair at a time, as the agent's rule 6.4 asks, so that
transfer mode costs no more than the agent's own random learning, and the can still joins the
database (with the pairs explored) once its functional pair is known.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from sklearn.utils import check_random_state

from behaviours.learners.baseline import PartBasedLearner, Session, SessionParams
from behaviours.learners.effect_models import LinearEffectModel
from behaviours.learners.known_objects import KnownObject, KnownObjectDatabase
from behaviours.learners.part_models import (
    Bounds,
    FunctionalPair,
    OpeningGoal,
    Pair,
    PartActionModel,
)
from behaviours.learners.protocol import ObjectView, Outcome, Trial
from behaviours.learners.similarity import rank_sources
from behaviours.learners.transfer import TransferLearner
from behaviours.learning import AffordanceEvidence, RandomExplorer
from behaviours.perception import Perception, part_displacement
from behaviours.skills import THETA_BOUNDS, perform_skill
from sim.world import GarbageWorld


class CanUnderTest:
    """One simulated can, seen through ``perception``, acted on by the motor skills."""

    def __init__(self, world: GarbageWorld, perception: Perception,
                 actions: Mapping[str, tuple[float, float]] = THETA_BOUNDS) -> None:
        self.world = world
        self.perception = perception
        self.name = world.can
        self.actions = dict(actions)
        self.initial_opening = world.opening()
        self.performed = 0

    def perceive(self) -> ObjectView:
        """The can as it stands now: parts, descriptors, relations, image positions, s_o."""
        seen = self.perception.observe(self.world)
        return ObjectView(
            parts={name: part.descriptor() for name, part in seen.parts.items()},
            above=frozenset(seen.above),
            positions={name: part.centre for name, part in seen.parts.items()},
            state=seen.opening,
        )

    def perform(self, part: str, action: str, theta: float) -> Outcome:
        """Reset the can to its initial opening, do action(θ) on part, measure (5.3, 5.15)."""
        self.world.set_opening(self.initial_opening)
        before = self.perception.observe(self.world)
        perform_skill(self.world, action, part, theta)
        self.performed += 1
        after = self.perception.observe(self.world)
        moved = part_displacement(before, after, part)
        return Outcome(part_displacement=moved, state_before=before.opening,
                       state_after=after.opening)

    def restore(self) -> None:
        """Leave the can as learning found it."""
        self.world.set_opening(self.initial_opening)


@dataclass(frozen=True)
class PairReport:
    """What a transfer run found about one (part, action) pair it tried (§6.3.3-6.3.4).

    ``evidence`` is afford(Part, Act, Eff, 1, 1, 1) for the pair whose action reached the goal,
    else afford(Part, Act, Eff, 0, 0, r1 | r2) by the pair's own model's e_max (6.10, 6.11,
    6.14); ``theta_max`` and ``e_max`` (6.13, 6.8) are read off ĥ(ĝ(θ)) over Θ.
    """

    evidence: AffordanceEvidence
    theta_max: float
    e_max: float
    actions: int  # how many of the run's actions were on this pair


@dataclass(frozen=True)
class TransferResult:
    """A transfer run on a simulated can: the learner, one report per pair tried."""

    learner: TransferLearner
    reports: tuple[PairReport, ...]
    known: KnownObject
    """The entry the can got in the database."""

    @property
    def actions(self) -> int:
        """Physical actions taken (N of Table 5.4)."""
        return self.learner.n_actions_


def _pair_report(models: Mapping[Pair, PartActionModel], bounds: Mapping[str, Bounds],
                 found: FunctionalPair | None, trials: Sequence[Trial], pair: Pair,
                 effect_name: str, delta: float, r1: float, r2: float) -> PairReport:
    """The evidence and (θ_max, e_max) of one pair tried, from the pair's model, the
    functional pair found (if any) and the trials that were on the pair."""
    model = models[pair]
    low, high = bounds[pair[1]]
    ends = model.predict([high, low + (high - low) * 1e-3])
    theta_max = high if ends[0] >= ends[1] else low + (high - low) * 1e-3
    e_max = float(max(ends))
    if found is not None and (found.part, found.action) == pair:
        evidence = AffordanceEvidence(pair[0], pair[1], effect_name, 1, 1, 1)
        theta_max = found.theta
    else:
        evidence = AffordanceEvidence(pair[0], pair[1], effect_name, 0, 0,
                                      r1 if e_max >= delta else r2)
    actions = sum((t.part, t.action) == pair for t in trials)
    return PairReport(evidence, float(theta_max), e_max, actions)


def relevant_sources(world: GarbageWorld, perception: Perception,
                     database: KnownObjectDatabase, *, delta: float = 0.1) -> list[str]:
    """Algorithm 5 on the can as it stands: the known objects it could transfer from, most
    similar first (what ``TransferLearner`` would choose from, with its parameters)."""
    p = TransferLearner(database=list(database), goal=delta).get_params()
    view = CanUnderTest(world, perception).perceive()
    candidates = rank_sources(
        p["database"], view, OpeningGoal(p["goal"], p["delta1"]), delta2=p["delta2"],
        similarity_params={"n_neighbors": p["n_neighbors"], "max_distance": p["max_distance"],
                           "weights": p["weights"]})
    return [candidate.known.name for candidate in candidates]


def learn_by_transfer(world: GarbageWorld, perception: Perception,
                      database: KnownObjectDatabase, *, delta: float = 0.1,
                      effect_name: str = "opened",
                      random_state: int | np.random.RandomState | None = None,
                      r1: float = 0.3, r2: float = 0.05,
                      other_parts: bool = True,
                      first_pair: tuple[str, str] | None = None) -> TransferResult:
    """Algorithm 6 on the can against ``database``, then remember the can in it.

    The can is left as learning found it; the database gets (or replaces) the entry named
    after the can, so the next can may transfer from this one. ``other_parts=False`` stops
    Algorithm 6 after the source's functional part (``TransferLearner.other_parts``);
    ``first_pair`` is checked first there (``TransferLearner.first_pair``).
    """
    can = CanUnderTest(world, perception)
    try:
        learner = TransferLearner(database=list(database), goal=delta,
                                  random_state=random_state, other_parts=other_parts,
                                  first_pair=first_pair).fit(can)
    finally:
        can.restore()
    known = KnownObject.learned(world.can, learner, extra={"can_file": world.spec.source})
    database.add(known)
    tried = list(dict.fromkeys((t.part, t.action) for t in learner.trials_))
    reports = tuple(_pair_report(learner.models_, learner.bounds_, learner.functional_,
                                 learner.trials_, pair, effect_name, delta, r1, r2)
                    for pair in tried)
    return TransferResult(learner, reports, known)


RANDOM_LEARNING = RandomExplorer()
"""The agent's random learning of one pair (its defaults: n_min, settle_tol), whose stopping
rule ``PairEpisode`` also follows."""


class PairEpisode:
    """Algorithm 4 on a can one pair at a time, in the order an agent asks about them.

    Each ``explore(part, action)`` is Algorithm 4's lines 3-8 for that pair (random θ until
    n samples or the pair's model settles as moving nothing, §5.4.2, or until the agent's
    random learning would stop, ``explored``), stopping early once an action opens the can
    (5.9), on the can as learning found it. The report is the one a transfer run gives for a
    pair it tried. With ``prior`` (what a transfer that stopped short learned on this can
    before), the episode goes on from that transfer's samples: a pair it tried is explored
    only up to Algorithm 4's n samples (or until dead) in all, so no action is tried twice
    over and a pair it explored fully costs nothing more (issue 32: a can that cannot be
    opened cost more than random learning when the agent's second episode explored the
    transferred part's pairs from scratch). Once the functional pair is known (an explored
    action opened the can, or ``verified`` says a use of a pair did), the can joins
    ``database`` with every pair explored, so that later cans can transfer from it; after a
    transfer, with its pairs, actions and source too.
    """

    def __init__(self, world: GarbageWorld, perception: Perception,
                 database: KnownObjectDatabase, *, delta: float = 0.1,
                 random_state: int | np.random.RandomState | None = None,
                 r1: float = 0.3, r2: float = 0.05, prior: KnownObject | None = None) -> None:
        self.world = world
        self.database = database
        self.prior = prior
        self.delta, self.r1, self.r2 = delta, r1, r2
        self.can = CanUnderTest(world, perception)
        rng = check_random_state(random_state)
        params = SessionParams.from_estimator(PartBasedLearner(goal=delta, random_state=rng))
        self.session = Session(self.can, params, rng)
        if prior is not None:  # copies: the database's entry for the can keeps its own
            self.session.models.update(
                {pair: copy.deepcopy(model) for pair, model in prior.models.items()})
        self.functional: FunctionalPair | None = None

    def explore(self, part: str, action: str, effect_name: str = "opened") -> PairReport:
        """Explore (part, action) as Algorithm 4 does, or as random learning does when that
        stops first (``explored``); the pair's evidence (§6.3.4)."""
        done = len(self.session.trials)
        try:
            while not self.explored((part, action)):
                self.session.act(part, action, self.session.random_theta(action), "explore")
                if self.session.reached:
                    break
        finally:
            self.can.restore()
        success = self.session.success
        if self.functional is None and success is not None:
            self.verified(success.part, success.action, success.theta)
        return _pair_report(self.session.models, self.session.bounds, self.functional,
                            self.session.trials[done:], (part, action), effect_name,
                            self.delta, self.r1, self.r2)

    def explored(self, pair: Pair) -> bool:
        """Whether exploring ``pair`` is over: by Algorithm 4 (n samples, or its model settled
        as moving nothing), or by the agent's random learning of one pair
        (``RandomExplorer``: the opening's line Ĥ(θ) settled, eq. 5.19, from its n_min-th
        sample on). Random learning stops a pair that moves its part without opening the
        can at four samples where Algorithm 4 takes five, so without its rule the agent
        learning by transfer, pair by pair, took more exploratory actions than learning
        randomly on the same can and seed (issue 32: a small push lid from nothing, 5
        against 4; o5, 45 against 44)."""
        model = self.session.models.get(pair)
        if model is None:
            return False
        p = self.session.params
        if model.n_samples_ >= p.n or self.session.dead(pair):
            return True
        if model.n_samples_ < RANDOM_LEARNING.n_min:
            return False
        line = LinearEffectModel()
        for theta, effect in zip(model.theta_, model.effect_, strict=True):
            line.partial_fit([theta], [effect])
        return line.settled(RANDOM_LEARNING.settle_tol)

    def verified(self, part: str, action: str, theta: float) -> None:
        """(part, action) with θ opened the can: remember the can with its functional pair
        (once; pairs never explored here are not this episode's to record)."""
        if self.functional is not None or (part, action) not in self.session.models:
            return
        self.functional = FunctionalPair(part, action, theta)
        view = self.session.view
        prior = self.prior
        models = {**(dict(prior.models) if prior else {}), **self.session.models}
        self.database.add(KnownObject(
            name=self.world.can, parts=dict(view.parts), above=frozenset(view.above),
            bounds=dict(self.session.bounds), models=models, functional=self.functional,
            n_actions=len(self.session.trials) + (prior.n_actions if prior else 0),
            source=prior.source if prior else None,
            extra={"can_file": self.world.spec.source}))
