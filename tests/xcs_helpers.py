"""Hand-built XCS populations for the XCS tests."""

from __future__ import annotations

from behaviours.learners.xcs import XCS, Classifier

NO_GA = 10**9
"""A GA threshold never reached: tests of the updates alone."""


def make(records: list[Classifier], *, n_actions: int = 2, time: int = 0, **params) -> XCS:
    params.setdefault("theta_ga", NO_GA)
    params.setdefault("N", 1000)
    xcs = XCS(n_actions, random_state=0, **params)
    xcs.set_classifiers(records, time=time)
    return xcs


def by_condition(xcs: XCS) -> dict[tuple[str, int], Classifier]:
    return {(c.condition, c.action): c for c in xcs.classifiers()}


def cl(condition: str, action: int, prediction: float = 10.0, error: float = 0.0,
       fitness: float = 0.01, experience: int = 0, numerosity: int = 1,
       action_set_size: float = 1.0, time_stamp: int = 0) -> Classifier:
    return Classifier(condition, action, prediction, error, fitness, experience, numerosity,
                      action_set_size, time_stamp)
