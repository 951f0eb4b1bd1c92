"""Similarity of parts and objects, and Algorithm 5: find relevant source objects (§5.5.3).

Parts are grouped by the k-nearest-neighbour classifier of scikit-learn over their Table 5.1
descriptors (area, rectangleness, squareness), trained on the parts of the known objects with
each part's name as its group ("similar parts are classified into the same group"). A part
farther than ``max_distance`` from every known part is novel: similar to nothing. Objects are
compared by counting the ``above`` relations they share once the target's parts are mapped to
their groups, as the thesis does; ties go to the object known first. (A tie-break on mean
descriptor distance was tried: in camera mode o2's body marker reads a few pixels off, and it
handed o5 to o4 instead of the thesis's o2 on every seed, on pixel noise rather than shape.)
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from sklearn.base import BaseEstimator, ClassifierMixin, _fit_context
from sklearn.neighbors import KNeighborsClassifier
from sklearn.utils.multiclass import check_classification_targets
from sklearn.utils.validation import check_is_fitted, validate_data

from behaviours.learners.known_objects import KnownObject
from behaviours.learners.part_models import OpeningGoal, Selection, select_part_action
from behaviours.learners.protocol import ObjectView
from behaviours.learners.validation import POSITIVE, POSITIVE_INT, as_rows

DEFAULT_WEIGHTS = (1000.0, 1.0, 1.0)
"""Weights putting (area, rectangleness, squareness) on like ranges before distances.

A marker's area is ~0.001..0.01 of the image while the ratios lie in 0..1, so area counts in
per-mille (standardising by the spread instead over-weights squareness, ~1 for every marker).
"""


class PartSimilarity(ClassifierMixin, BaseEstimator):
    """k-nearest-neighbour groups of parts over weighted Table 5.1 descriptors.

    ``fit(X, y)``: X one descriptor per known part, y its group (the part's name). Neighbours
    vote weighted by inverse distance, so one close part outvotes two far ones. ``weights``
    scale the descriptor's values before distances (None: unweighted); a part farther than
    ``max_distance`` from every known part is novel, predicted None (None: no part is novel).
    """

    _parameter_constraints: ClassVar[dict[str, list]] = {
        "n_neighbors": [POSITIVE_INT], "weights": ["array-like", None],
        "max_distance": [POSITIVE, None],
    }

    def __init__(self, n_neighbors: int = 3, weights: Sequence[float] | None = DEFAULT_WEIGHTS,
                 max_distance: float | None = 1.0) -> None:
        self.n_neighbors = n_neighbors
        self.weights = weights
        self.max_distance = max_distance

    def _weigh(self, X: np.ndarray) -> np.ndarray:
        """Validated descriptors times the weights (a weight per value, or a clear error)."""
        if self.weights is None:
            return X
        weights = np.asarray(self.weights, dtype=float)
        if weights.shape != (X.shape[1],):
            raise ValueError(f"descriptors must have {weights.size} values each (one per "
                             f"weight), got {X.shape[1]}")
        return X * weights

    @_fit_context(prefer_skip_nested_validation=True)
    def fit(self, X: object, y: Sequence[str]) -> PartSimilarity:
        """Remember the known parts' descriptors and groups."""
        X, y = validate_data(self, X, y, dtype=np.float64)
        check_classification_targets(y)
        points = self._weigh(X)
        self.classifier_ = KNeighborsClassifier(
            n_neighbors=min(self.n_neighbors, points.shape[0]), weights="distance"
        ).fit(points, y)
        self.classes_ = self.classifier_.classes_
        self.n_parts_ = points.shape[0]
        return self

    def predict(self, X: object) -> np.ndarray:
        """The group of each descriptor, or None where the part is novel."""
        check_is_fitted(self, "classifier_")
        points = self._weigh(validate_data(self, X, reset=False, dtype=np.float64))
        groups = self.classifier_.predict(points)
        if self.max_distance is None:
            return groups
        groups = groups.astype(object)  # to hold None
        distances, _ = self.classifier_.kneighbors(points, n_neighbors=1)
        groups[distances[:, 0] > self.max_distance] = None
        return groups

    def group(self, descriptor: object) -> str | None:
        """The group of one part (None: novel)."""
        return self.predict([descriptor])[0]

    def distance(self, a: object, b: object) -> float:
        """Weighted Euclidean distance between two descriptors."""
        first, second = (self._weigh(as_rows(np.atleast_1d(np.asarray(v, dtype=float))[None, :],
                                             "descriptor")) for v in (a, b))
        return float(np.linalg.norm(first[0] - second[0]))


def fit_similarity(objects: Iterable[KnownObject], **params: object) -> PartSimilarity | None:
    """A PartSimilarity trained on every part of ``objects`` (None if there are no parts)."""
    descriptors, groups = [], []
    for known in objects:
        for name, descriptor in known.parts.items():
            descriptors.append(descriptor)
            groups.append(name)
    if not descriptors:
        return None
    return PartSimilarity(**params).fit(descriptors, groups)


def similar_part(similarity: PartSimilarity, view: ObjectView, group: str,
                 descriptor: object, exclude: Iterable[str] = ()) -> str | None:
    """The part of ``view`` in ``group`` nearest to ``descriptor`` (lines 5, 25 of Alg. 6)."""
    skip = set(exclude)
    names = [name for name in view.parts if name not in skip]
    if not names:
        return None
    groups = similarity.predict([view.parts[name] for name in names])
    members = [name for name, g in zip(names, groups, strict=True) if g == group]
    if not members:
        return None
    return min(members, key=lambda name: similarity.distance(view.parts[name], descriptor))


def shared_relations(similarity: PartSimilarity, view: ObjectView, known: KnownObject) -> int:
    """How many of the target's ``above`` relations, mapped to groups, the known object has."""
    names = list(view.parts)
    group_of = dict(zip(names, similarity.predict([view.parts[n] for n in names]), strict=True))
    mapped = {(group_of[a], group_of[b]) for a, b in view.above
              if group_of.get(a) is not None and group_of.get(b) is not None}
    return len(mapped & set(known.above))


@dataclass(frozen=True)
class SourceCandidate:
    """A relevant source object (Algorithm 5) and the parts that make it relevant."""

    known: KnownObject
    rehearsal: Selection  # ψ*, a*, θ* of the known object for the target's task (lines 4-5)
    target_part: str  # the target's part similar to ψ* (line 7)
    shared_relations: int


def rehearse(known: KnownObject, goal: OpeningGoal, initial_state: float,
             delta2: float) -> Selection | None:
    """Lines 4-5 of Algorithm 5 (2-4 of Algorithm 6): 5.11/5.12 on the known object's models
    as if it were in the target's initial state with the target's goal."""
    return select_part_action(known.models, known.bounds, goal.desired_effect(initial_state),
                              delta1=goal.delta1, delta2=delta2)


def rank_sources(objects: Iterable[KnownObject], view: ObjectView, goal: OpeningGoal, *,
                 delta2: float = 0.002,
                 similarity_params: Mapping[str, object] | None = None
                 ) -> list[SourceCandidate]:
    """Algorithm 5: the known objects whose functional part looks like a part of the target,
    most similar first: by the number of shared ``above`` relations (§5.5.3), ties in the
    order the objects became known (the stable sort keeps the database's order)."""
    known_objects = list(objects)
    similarity = fit_similarity(known_objects, **dict(similarity_params or {}))
    if similarity is None:
        return []
    ranked: list[tuple[tuple[int, int], SourceCandidate]] = []
    for index, known in enumerate(known_objects):
        rehearsal = rehearse(known, goal, view.state, delta2)
        if rehearsal is None:
            continue
        target = similar_part(similarity, view, rehearsal.part, known.parts[rehearsal.part])
        if target is None:
            continue
        shared = shared_relations(similarity, view, known)
        ranked.append(((-shared, index), SourceCandidate(known, rehearsal, target, shared)))
    return [candidate for _, candidate in sorted(ranked, key=lambda item: item[0])]
