"""scikit-learn's own estimator checks on the learners (thesis chapters 3-6).

Estimators with scikit-learn's ``fit(X, y)`` / ``predict(X)`` run every check of
``check_estimator`` (``parametrize_with_checks``), each with parameters that put scikit-learn's
test data inside the learner's domain (the domain itself is declared by its tags and tested in
the learner's own test file). The learners that do not learn from (X, y) — XCS and CACLA learn
from rewards, Algorithms 4 and 6 from an object they act on, Algorithm 3 from a world — are
``BaseEstimator``s all the same: they run the checks of the estimator API that need no ``fit``.
"""

from __future__ import annotations

import pytest
from sklearn.utils import get_tags
from sklearn.utils.estimator_checks import parametrize_with_checks

from behaviours.learners.baseline import PartBasedLearner
from behaviours.learners.cacla import CACLA
from behaviours.learners.effect_models import LinearEffectModel
from behaviours.learners.exploration import ActiveExplorer
from behaviours.learners.forward_model import ForwardModel
from behaviours.learners.part_models import PartActionModel
from behaviours.learners.similarity import PartSimilarity
from behaviours.learners.tags import DomainInputTags
from behaviours.learners.transfer import TransferLearner
from behaviours.learners.xcs import XCS, XCSClassifier

ESTIMATORS = [
    XCSClassifier(n_iter=2, binarize=0.0),  # binarize: the checks' features are real numbers
    # action bounds that hold the checks' data (the last column is the action)
    ForwardModel(action_bounds=((-1e3, 1e3),), learning_rate=0.01),
    LinearEffectModel(),
    # unweighted, and no part novel: the checks' features are not Table 5.1's three, and
    # their labels must all be classes
    PartSimilarity(weights=None, max_distance=None),
]
EXPECTED_FAILURES: dict[str, dict[str, str]] = {
    "LinearEffectModel": {
        "check_fit1d": "a 1-D X is one action parameter θ per sample, the way the behaviours "
                       "fit Ĥ(θ) (eq. 5.16, 6.7); a fitted model with several parameters "
                       "refuses 1-D X (check_fit2d_predict1d passes)",
    },
}
"""Per estimator class, the checks expected to fail and why."""


def expected_failures(estimator: object) -> dict[str, str]:
    return EXPECTED_FAILURES.get(type(estimator).__name__, {})


@parametrize_with_checks(ESTIMATORS, expected_failed_checks=expected_failures)
def test_scikit_learn_checks(estimator, check):
    check(estimator)


def test_domain_tags():
    assert get_tags(XCSClassifier()).input_tags.binary
    assert not get_tags(XCSClassifier(binarize=0.5)).input_tags.binary
    assert isinstance(get_tags(XCS(2)).input_tags, DomainInputTags)
    assert get_tags(XCS(2)).input_tags.binary
    model_tags = get_tags(ForwardModel())
    assert model_tags.input_tags.bounded_actions and model_tags.target_tags.multi_output


@pytest.mark.parametrize("estimator", [XCS(2), CACLA(), ActiveExplorer(), PartActionModel(),
                                       PartBasedLearner(), TransferLearner()],
                         ids=lambda e: type(e).__name__)
def test_estimator_api_without_fit(estimator):
    from sklearn.utils import estimator_checks as checks

    name = type(estimator).__name__
    for check in (checks.check_estimator_cloneable, checks.check_estimator_repr,
                  checks.check_no_attributes_set_in_init, checks.check_get_params_invariance,
                  checks.check_set_params, checks.check_parameters_default_constructible,
                  checks.check_do_not_raise_errors_in_init_or_set_params,
                  checks.check_valid_tag_types, checks.check_estimator_tags_renamed,
                  checks.check_mixin_order):
        check(name, estimator)
