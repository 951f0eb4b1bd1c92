"""Statistics over seeds, with scipy.stats: every mean with its sample sd (ddof = 1) and a 95%
bootstrap CI, every claim with an exact paired permutation test, its p-value, an effect size
and a verdict in words.

The test is the sign-flip permutation test of the mean difference (paired by seed, or each
seed against a number): exact, enumerating all 2^n sign patterns, up to n = 16 seeds, and a
seeded Monte Carlo test beyond. The effect size is the matched-pairs rank-biserial
correlation r (Kerby 2014; -1..1, 0 when no seed differs), beside the mean difference and its
bootstrap CI. Every resampling is seeded from the metric's name, so a page redrawn from its
JSON is the same byte for byte.
"""

from __future__ import annotations

import math
import zlib
from collections.abc import Sequence

import numpy as np
from pydantic import BaseModel, ConfigDict

from robot.reproduce.framework.study import Claim, Metric, SeedResult

CONFIDENCE = 0.95
ALPHA = 0.05
"""A claim is supported (or contradicted) at this level."""
BOOTSTRAP_RESAMPLES = 10_000
PERMUTATIONS = 2 ** 16
"""Sign patterns of the permutation test: all of them up to 16 seeds."""
PERMUTATION_BATCH = 2 ** 12
"""Sign patterns scipy draws and averages at a time. A divisor of PERMUTATIONS, so the random
patterns (each batch drawn on from the same generator) and the p-values are those of one
whole batch; the smaller arrays make a test of 20 or 30 seeds about three times faster and
one of 16 (exact) 40% faster."""


class Frozen(BaseModel):
    model_config = ConfigDict(frozen=True, extra="forbid")


class MetricSummary(Frozen):
    """A metric over the seeds that have it."""

    key: str
    label: str
    n: int
    """Seeds with a value."""
    seeds: int
    """Seeds run."""
    mean: float | None
    sd: float | None
    """Sample standard deviation (ddof = 1); None for fewer than two values."""
    ci: tuple[float, float] | None
    """95% bootstrap CI of the mean (percentile method)."""
    reference: float | None
    source: str

    @property
    def gap(self) -> float | None:
        """mean - reference, when both exist."""
        if self.mean is None or self.reference is None:
            return None
        return self.mean - self.reference


class Comparison(Frozen):
    """A claim's test over the seeds."""

    claim: str
    metric: str
    versus: str | float
    direction: str
    n: int
    """Seeds with both values (with the metric's value, against a number)."""
    test: str
    mean_difference: float | None
    ci: tuple[float, float] | None
    """95% bootstrap CI of the mean difference."""
    p_value: float | None
    p_opposite: float | None = None
    """The p-value of the opposite one-sided test (a directed claim is contradicted when it
    is at most α)."""
    smallest_p: float | None = None
    """The smallest p-value the test could give with these seeds (1/2^k one-sided, 2/2^k
    two-sided, k the seeds whose difference is not 0): above α, no outcome could reach it."""
    effect_size: float | None
    """Matched-pairs rank-biserial correlation r."""
    verdict: str
    """supported, not supported or contradicted (``same`` claims: not contradicted or
    contradicted); not tested without any seed."""


class Summary(Frozen):
    """The statistics a page shows: every metric and every claim's test."""

    confidence: float = CONFIDENCE
    alpha: float = ALPHA
    metrics: list[MetricSummary]
    comparisons: list[Comparison]


def summarize(metrics: Sequence[Metric], claims: Sequence[Claim],
              seeds: Sequence[SeedResult]) -> Summary:
    """Every metric's mean, sd and CI, and every claim's test, over ``seeds``."""
    values = {metric.key: [_number(metric.value(seed)) for seed in seeds] for metric in metrics}
    rows = [describe(metric, values[metric.key]) for metric in metrics]
    return Summary(metrics=rows, comparisons=[test(claim, values) for claim in claims])


def _number(value: float | bool | None) -> float | None:
    return None if value is None else float(value)


def describe(metric: Metric, values: Sequence[float | None]) -> MetricSummary:
    present = np.array([v for v in values if v is not None], dtype=float)
    mean = float(np.mean(present)) if len(present) else None
    sd = float(np.std(present, ddof=1)) if len(present) > 1 else None
    return MetricSummary(key=metric.key, label=metric.label, n=len(present), seeds=len(values),
                         mean=mean, sd=sd, ci=mean_interval(present, metric.key),
                         reference=metric.reference, source=metric.source)


def mean_interval(values: np.ndarray, name: str) -> tuple[float, float] | None:
    """The 95% percentile bootstrap CI of the mean, resampled with a generator seeded from
    ``name``; None for fewer than two values, the value itself when all are equal."""
    from scipy.stats import bootstrap

    if len(values) < 2:
        return None
    if np.all(values == values[0]):
        return float(values[0]), float(values[0])
    result = bootstrap((values,), np.mean, confidence_level=CONFIDENCE,
                       n_resamples=BOOTSTRAP_RESAMPLES, method="percentile",
                       rng=np.random.default_rng(_seed(name)))
    interval = result.confidence_interval
    return float(interval.low), float(interval.high)


def _seed(name: str) -> int:
    return zlib.crc32(name.encode())


def test(claim: Claim, values: dict[str, list[float | None]]) -> Comparison:
    """The claim's sign-flip permutation test over the seeds with both values."""
    if claim.metric not in values or (isinstance(claim.versus, str)
                                      and claim.versus not in values):
        raise ValueError(f"claim {claim.text!r} names a metric the study does not have")
    first = values[claim.metric]
    second = (values[claim.versus] if isinstance(claim.versus, str)
              else [float(claim.versus)] * len(first))
    differences = np.array([a - b for a, b in zip(first, second, strict=True)
                            if a is not None and b is not None], dtype=float)
    n = len(differences)
    name = f"{claim.metric} vs {claim.versus}"
    if n == 0:
        return Comparison(claim=claim.text, metric=claim.metric, versus=claim.versus,
                          direction=claim.direction, n=0, test="not tested: no seed has both "
                          "values", mean_difference=None, ci=None, p_value=None,
                          smallest_p=None, effect_size=None, verdict="not tested")
    p_value, p_opposite = sign_flip_ps(differences, claim.direction, name)
    exact = 2 ** n <= PERMUTATIONS
    sides = "two-sided" if claim.direction == "same" else f"one-sided ({claim.direction})"
    paired = ("paired by seed" if isinstance(claim.versus, str)
              else f"each seed against {claim.versus:g}")
    test_text = (f"sign-flip permutation test of the mean difference, {paired}, {sides}, "
                 + (f"exact over all {2 ** n:,} sign patterns" if exact else
                    f"{PERMUTATIONS:,} seeded random sign patterns") + f", n = {n}")
    return Comparison(claim=claim.text, metric=claim.metric, versus=claim.versus,
                      direction=claim.direction, n=n, test=test_text,
                      mean_difference=float(np.mean(differences)),
                      ci=mean_interval(differences, name), p_value=p_value,
                      p_opposite=None if claim.direction == "same" else p_opposite,
                      smallest_p=smallest_p(differences, claim.direction),
                      effect_size=rank_biserial(differences),
                      verdict=verdict(claim.direction, p_value, p_opposite))


def sign_flip_p(differences: np.ndarray, direction: str, name: str) -> float:
    """p-value of the sign-flip permutation test of mean(differences) (``same``: two-sided)."""
    return sign_flip_ps(differences, direction, name)[0]


def sign_flip_ps(differences: np.ndarray, direction: str,
                 name: str) -> tuple[float, float]:
    """The sign-flip test's p-value in ``direction`` and in the opposite one (``same``: the
    two-sided one, twice). One permutation test: the opposite p-value is counted on the null
    distribution scipy drew (the same for either direction: the draws are seeded from
    ``name``) exactly as scipy counts it, a tolerance of 100 ε relative to the observed mean,
    count / 2^n exact or (count + 1) / (draws + 1) drawn; the numbers of a second test,
    without its second enumeration of the sign patterns."""
    from scipy.stats import permutation_test

    opposite = {"greater": "less", "less": "greater", "same": "same"}[direction]
    if np.all(differences == 0):
        return 1.0, 1.0
    if len(differences) == 1:  # two sign patterns, ±d (scipy wants two values at least)
        def one(side: str) -> float:
            return 0.5 if {"greater": differences[0] > 0, "less": differences[0] < 0,
                           "same": False}[side] else 1.0
        return one(direction), one(opposite)
    alternative = {"greater": "greater", "less": "less", "same": "two-sided"}[direction]
    result = permutation_test((differences,), _mean, permutation_type="samples",
                              vectorized=True, n_resamples=PERMUTATIONS, batch=PERMUTATION_BATCH,
                              alternative=alternative, rng=np.random.default_rng(_seed(name)))
    p_value = float(min(1.0, result.pvalue))
    if opposite == direction:
        return p_value, p_value
    null, observed = result.null_distribution, result.statistic
    gamma = abs(np.finfo(np.float64).eps * 100 * observed)
    extreme = (null <= observed + gamma) if opposite == "less" else (null >= observed - gamma)
    adjustment = 0 if 2 ** len(differences) <= PERMUTATIONS else 1  # exact: all patterns
    count = np.count_nonzero(extreme) + adjustment
    return p_value, float(min(1.0, count / (len(null) + adjustment)))


def smallest_p(differences: np.ndarray, direction: str) -> float:
    """The least p-value the sign-flip test can give: only the observed signs (and their
    mirror image, two-sided) as extreme; a difference of 0 flips to itself."""
    varying = int(np.count_nonzero(differences))
    return min(1.0, (2 if direction == "same" else 1) / 2 ** varying)


def _mean(sample: np.ndarray, axis: int) -> np.ndarray:
    return np.mean(sample, axis=axis)


def rank_biserial(differences: np.ndarray) -> float:
    """Matched-pairs rank-biserial correlation: (R+ - R-) / (R+ + R-) over the ranks of the
    non-zero |differences| (average ranks for ties); 0 when every difference is 0."""
    from scipy.stats import rankdata

    nonzero = differences[differences != 0]
    if len(nonzero) == 0:
        return 0.0
    ranks = rankdata(np.abs(nonzero))
    return float((ranks[nonzero > 0].sum() - ranks[nonzero < 0].sum()) / ranks.sum())


def verdict(direction: str, p_value: float, p_opposite: float) -> str:
    """The verdict word: a directed claim is supported when its test rejects at ALPHA and
    contradicted when the opposite one does; a ``same`` claim is contradicted when the
    two-sided test rejects, and otherwise only not contradicted."""
    if direction == "same":
        return "contradicted" if p_value <= ALPHA else "not contradicted"
    if p_value <= ALPHA:
        return "supported"
    return "contradicted" if p_opposite <= ALPHA else "not supported"


def reading(comparison: Comparison) -> str:
    """The verdict as a sentence for the page."""
    if comparison.p_value is None or comparison.mean_difference is None:
        return "Not tested: no seed has both values."
    versus = (f"`{comparison.versus}`" if isinstance(comparison.versus, str)
              else f"{comparison.versus:g}")
    ci = ("" if comparison.ci is None else
          f", 95% CI [{number(comparison.ci[0])}, {number(comparison.ci[1])}]")
    measured = (f"mean difference `{comparison.metric}` − {versus} = "
                f"{number(comparison.mean_difference)}{ci}; p = {p_text(comparison.p_value)}; "
                f"rank-biserial r = {comparison.effect_size:+.2f}")
    words = {
        "supported": f"**supported** at α = {ALPHA:g}",
        "not supported": f"**not supported** at α = {ALPHA:g}: the difference is not "
                         "significant",
        "contradicted": f"**contradicted** at α = {ALPHA:g}" + (
            ": the seeds differ" if comparison.direction == "same"
            else ": the difference goes significantly the other way (the opposite one-sided "
                 f"test: p = {p_text(comparison.p_opposite or 0.0)})"),
        "not contradicted": f"**not contradicted** at α = {ALPHA:g}: no significant "
                            "difference (which does not show equality)",
    }[comparison.verdict]
    if comparison.smallest_p is not None and comparison.smallest_p > ALPHA:
        measured += (f"; with these {comparison.n} seeds no outcome could reach α: the "
                     f"smallest possible p is {p_text(comparison.smallest_p)}")
    return f"{words} ({measured})."


def p_text(p_value: float) -> str:
    """A p-value to two significant digits (three decimals below 0.001)."""
    return f"{p_value:.2g}" if p_value >= 0.001 else f"{p_value:.1e}"


def number(value: float | None) -> str:
    """Four significant digits (whole thousands grouped); an em dash for a missing value."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "—"
    if abs(value) >= 1000:
        return f"{value:,.0f}"
    return f"{value:.4g}"
