"""Estimator tags for the learners' domain limits that scikit-learn has no tag for.

scikit-learn's ``InputTags`` say whether X may be sparse, hold NaN, be 1-D or must be
positive; the learners also need to say that every feature must be a bit (XCS's ternary
conditions match bits) and that the last columns of X are actions refused outside the
estimator's ``action_bounds`` (the forward model, eq. 4.1). ``DomainInputTags`` adds those two
fields to scikit-learn's dataclass, so ``sklearn.utils.get_tags`` and the common checks still
see a valid ``InputTags``.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from sklearn.utils import InputTags, Tags

__all__ = ["DomainInputTags", "with_domain"]


@dataclass(slots=True)
class DomainInputTags(InputTags):
    """scikit-learn's input tags and two more for the learners' domains."""

    binary: bool = False
    """Every feature of X must be 0 or 1."""
    bounded_actions: bool = False
    """The last columns of X are actions, refused outside the estimator's action bounds."""


def with_domain(tags: Tags, *, binary: bool = False, bounded_actions: bool = False) -> Tags:
    """``tags`` with its input tags replaced by `DomainInputTags` carrying the same values."""
    current = {field.name: getattr(tags.input_tags, field.name)
               for field in fields(InputTags)}
    tags.input_tags = DomainInputTags(**current, binary=binary,
                                      bounded_actions=bounded_actions)
    return tags
