"""What the ``garbage`` environment does with an agent's ``learn`` and ``apply`` (thesis §6.3).

``AffordanceRequests`` carries out a checked request and returns the percepts it yields:
random and active learning of one pair (``behaviours.learning``), transfer learning
(``behaviours.part_learning``: Algorithm 6 when a known object is relevant, then Algorithm 4
a pair at a time, as the agent asks), and the verified use of an affordance. Asked about a
pair, Algorithm 6 runs up to line 23 only: the source's functional pair on the can's
look-alike part and one try of every other action there. The other parts are the agent's to
learn a pair at a time, in its own order (rule 6.4): Algorithm 6's one-try checks of the
other look-alike parts (a body, say) and its fixed-order Algorithm 4 on the novel ones (a
pedal) made it cost more than the agent learning randomly on cans whose functional part no
known object has (issue 32). The whole-object form ``learn(Eff, transfer)`` is Algorithm 6
in full.
It also keeps the livelock guard: a request already answered since the world last changed
other than by learning would get the same answer, so it is not run again and the percept
``learn_repeated(...)`` (the request's own arguments) says so instead (issue 32).
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterable
from pathlib import Path

import numpy as np

from behaviours.learners.known_objects import KnownObject, KnownObjectDatabase
from behaviours.learning import AffordanceBehaviours, AffordanceEvidence, LearningModeUnavailable
from behaviours.part_learning import PairEpisode, PairReport, learn_by_transfer, relevant_sources
from behaviours.perception import Perception
from goalagent.eis.exceptions import ActionRefused
from goalagent.eis.pyenv import PerceptLike
from goalagent.kb.terms import Atom, Struct
from sim.world import GarbageWorld


def afford_percept(evidence: AffordanceEvidence) -> Struct:
    """The percept ``afford(Obj, Act, Eff, Tot, Suc, Rel)`` (eq. 6.1) for what a behaviour found."""
    return Struct("afford", (Atom(evidence.obj), Atom(evidence.act), Atom(evidence.eff),
                             evidence.tot, evidence.suc, evidence.rel))


class AffordanceRequests:
    """The learn and apply requests on one can, and what has been answered since the world
    last changed other than by learning."""

    def __init__(self, world: GarbageWorld, perception: Perception,
                 behaviours: AffordanceBehaviours, objects: KnownObjectDatabase, *,
                 delta: float, seed: int) -> None:
        self.world = world
        self.perception = perception
        self.behaviours = behaviours
        self.objects = objects
        self.delta = delta
        self._transfer_rng = np.random.RandomState(seed)
        self._answered: set[tuple[str, ...]] = set()
        self._pairs: PairEpisode | None = None
        self._transferred: KnownObject | None = None
        self._told: set[str] = set()

    def world_changed(self) -> None:
        """Something other than learning changed the world: every question may be asked
        again."""
        self._answered.clear()

    def learn(self, asked: tuple[str, ...], effect: str, mode: str) -> list[PerceptLike]:
        """Carry out ``learn(*asked)`` (checked by the environment): four arguments (Part,
        Act, Eff, Mode) or the whole-object form (Eff, transfer); its percepts."""
        events: list[PerceptLike] = []
        if mode != "transfer":
            part, action_type = asked[:2]
            self._once(asked, events, lambda: self._learn_pair(part, action_type, effect, mode))
        elif len(asked) == 4 and self._pair_by_pair():
            part, action_type = asked[:2]
            self._once(asked, events,
                       lambda: self._learn_pair_by_transfer(part, action_type, effect))
        else:
            whole = len(asked) == 2
            first = None if whole else (asked[0], asked[1])
            self._once((effect, mode), events,
                       lambda: self._learn_by_transfer(effect, other_parts=whole,
                                                       first_pair=first))
        return events

    def apply(self, part: str, action_type: str) -> list[PerceptLike]:
        """Act with the best known θ (eq. 6.13); the verified ``afford`` percept (§6.3.3).
        A success on a can learned a pair at a time completes what is known of it."""
        result = self.behaviours.apply(part, action_type)
        if result.evidence.suc and self._pairs is not None:
            self._pairs.verified(part, action_type, result.theta)
        self.world_changed()
        return [afford_percept(result.evidence)]

    def _once(self, request: tuple[str, ...], events: list[PerceptLike],
              run: Callable[[], list[PerceptLike]]) -> None:
        """Run a request unless it was answered since the world last changed other than by
        learning: then the percept ``learn_repeated(...)`` says so instead."""
        if request in self._answered:
            events.append(Struct("learn_repeated", tuple(Atom(a) for a in request)))
            return
        events.extend(run())
        self._answered.add(request)

    def _learn_pair(self, part: str, action_type: str, effect: str,
                    mode: str) -> list[PerceptLike]:
        """Random or active learning of one pair (§6.3.4); afford/model/exploration percepts."""
        try:
            result = self.behaviours.learn(part, action_type, effect, mode)
        except LearningModeUnavailable as error:
            raise ActionRefused(str(error)) from None
        if self.behaviours.store is not None:
            self._tell_where("learned effect models", self.behaviours.store.path)
        return [afford_percept(result.evidence),
                Struct("model", (Atom(part), Atom(action_type), round(result.theta_max, 4),
                                 round(result.e_max, 4))),
                Struct("exploration", (Atom(part), Atom(action_type), Atom(mode),
                                       result.samples))]

    def _pair_by_pair(self) -> bool:
        """Whether transfer goes on a pair at a time on this can: once Algorithm 6 has had
        its turn (what it found is the agent's, and the can's entry keeps it; asked again,
        it would only transfer from this can itself), and from the start when no known
        object is relevant to the can (Algorithm 5 finds no source, so Algorithm 6 would be
        Algorithm 4 on every pair)."""
        if self._pairs is None and (self._transferred is not None or not relevant_sources(
                self.world, self.perception, self.objects, delta=self.delta)):
            self._pairs = PairEpisode(self.world, self.perception, self.objects,
                                      delta=self.delta, random_state=self._transfer_rng,
                                      prior=self._transferred)
        return self._pairs is not None

    def _learn_pair_by_transfer(self, part: str, action_type: str,
                                effect: str) -> list[PerceptLike]:
        """Algorithm 4 on one pair, nothing (more) to transfer from (``PairEpisode``)."""
        assert self._pairs is not None
        report = self._pairs.explore(part, action_type, effect)
        self._tell_where("known objects", self.objects.path)
        return self._report_pairs([report])

    def _learn_by_transfer(self, effect: str, other_parts: bool,
                           first_pair: tuple[str, str] | None) -> list[PerceptLike]:
        """Algorithm 6 on this can (past the source's functional part only if
        ``other_parts``; the pair the agent asked about checked first of the other actions
        if it is on the part transfer works on); afford/model percepts for every pair tried
        (§5.5.4), and
        ``transferred(Eff, Source)`` (``none``: no known object was relevant, so it was
        Algorithm 4 on every pair)."""
        result = learn_by_transfer(self.world, self.perception, self.objects, delta=self.delta,
                                   effect_name=effect, random_state=self._transfer_rng,
                                   other_parts=other_parts, first_pair=first_pair)
        self._transferred = result.known
        self._tell_where("known objects", self.objects.path)
        source = result.learner.source_
        return [*self._report_pairs(result.reports),
                Struct("transferred", (Atom(effect), Atom(source or "none")))]

    def _report_pairs(self, reports: Iterable[PairReport]) -> list[PerceptLike]:
        """afford/model/exploration percepts of the pairs a transfer tried; θ_max of those
        it verified or predicts effective is what ``apply`` uses (eq. 6.13)."""
        events: list[PerceptLike] = []
        for report in reports:
            evidence = report.evidence
            if evidence.suc or report.e_max >= self.delta:  # verified, or 6.10
                self.behaviours.remember(evidence.obj, evidence.act, report.theta_max)
            events += [afford_percept(evidence),
                       Struct("model", (Atom(evidence.obj), Atom(evidence.act),
                                        round(report.theta_max, 4), round(report.e_max, 4))),
                       Struct("exploration", (Atom(evidence.obj), Atom(evidence.act),
                                              Atom("transfer"), report.actions))]
        return events

    def _tell_where(self, what: str, path: Path) -> None:
        """Say once per run where learning keeps what it wrote (stderr), so a user can find,
        keep or delete it."""
        if what not in self._told:
            self._told.add(what)
            print(f"garbage: {what} are kept in {path}", file=sys.stderr)
