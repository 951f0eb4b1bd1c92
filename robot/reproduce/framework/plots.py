"""The figures of a page: curves over seeds (their mean with a 95% bootstrap CI band, the
thesis's values as dashed lines), and a sweep's metric against the swept parameter (every
seed's value, the mean and its CI). Drawn with matplotlib's Agg canvas into PNG bytes."""

from __future__ import annotations

import io
import warnings
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

CONFIDENCE = 0.95
BAND_RESAMPLES = 2000
"""Bootstrap resamples for a curve's CI band (each point of a curve has its own CI)."""
BAND_SEED = 20_240_601
"""The band's resampling is seeded, so a redrawn page is byte for byte the same."""
REFERENCE_STYLES = ({"linestyle": "--", "color": "0.25"}, {"linestyle": ":", "color": "firebrick"},
                    {"linestyle": "-.", "color": "darkgreen"})
"""How reference lines look, in the order a panel lists them."""


@dataclass(frozen=True)
class Series:
    """One curve: the same x for every seed, one y list per seed (NaN: no value there)."""

    label: str
    x: Sequence[float]
    runs: Sequence[Sequence[float]]


@dataclass(frozen=True)
class Reference:
    """A reference value drawn as a dashed line (horizontal, or vertical with ``vertical``)."""

    value: float
    label: str
    vertical: bool = False


@dataclass(frozen=True)
class Panel:
    """One set of axes."""

    xlabel: str
    ylabel: str
    series: Sequence[Series]
    references: Sequence[Reference] = ()
    ylim: tuple[float, float] | None = None


@dataclass(frozen=True)
class Figure:
    """One PNG, ``<out>/<study>-<stem>.png``, with panels side by side."""

    stem: str
    title: str
    panels: Sequence[Panel]


def curve_band(runs: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per x: the mean over seeds and its 95% bootstrap CI (percentile; seeds without a value
    at that x are left out). One seed: the band is the curve itself."""
    from scipy.stats import bootstrap

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # an x where no seed has a value
        mean = np.nanmean(runs, axis=0)
        if runs.shape[0] < 2:
            return mean, mean, mean
        interval = bootstrap((runs,), np.nanmean, axis=0, confidence_level=CONFIDENCE,
                             n_resamples=BAND_RESAMPLES, batch=100, method="percentile",
                             rng=np.random.default_rng(BAND_SEED)).confidence_interval
    return mean, interval.low, interval.high


def _canvas(panels: int, width: float = 5.2):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure as Canvas

    canvas = Canvas(figsize=(width * panels, 3.8), layout="constrained")
    FigureCanvasAgg(canvas)
    return canvas, canvas.subplots(1, panels, squeeze=False)[0]


def _png(canvas) -> bytes:
    buffer = io.BytesIO()
    canvas.savefig(buffer, format="png", dpi=110, metadata={"Software": None})
    return buffer.getvalue()


def render_figure(figure: Figure, n_seeds: int) -> bytes:
    """The figure as PNG bytes: each series' mean over seeds with its 95% CI band."""
    canvas, axes = _canvas(len(figure.panels))
    for ax, panel in zip(axes, figure.panels, strict=True):
        for series in panel.series:
            runs = np.asarray(series.runs, dtype=float)
            if runs.ndim != 2 or runs.shape[1] != len(series.x):
                raise ValueError(f"figure {figure.stem}: series {series.label!r} needs one run "
                                 f"of {len(series.x)} values per seed")
            mean, low, high = curve_band(runs)
            line, = ax.plot(series.x, mean,
                            label=f"{series.label} (mean, 95% CI, {n_seeds} seeds)")
            ax.fill_between(series.x, low, high, alpha=0.25, color=line.get_color(),
                            linewidth=0)
        for index, reference in enumerate(panel.references):
            draw = ax.axvline if reference.vertical else ax.axhline
            style = REFERENCE_STYLES[index % len(REFERENCE_STYLES)]
            draw(reference.value, linewidth=1.2, label=reference.label, **style)
        ax.set_xlabel(panel.xlabel)
        ax.set_ylabel(panel.ylabel)
        if panel.ylim is not None:
            ax.set_ylim(*panel.ylim)
        ax.grid(alpha=0.3)
        ax.legend(fontsize="small")
    canvas.suptitle(figure.title)
    return _png(canvas)


@dataclass(frozen=True)
class SweepLine:
    """One metric over the swept values: per value, every seed's number and the mean's CI."""

    label: str
    points: Sequence[Sequence[float]]
    """Per swept value, the seeds' values (those that have one)."""
    means: Sequence[float | None]
    intervals: Sequence[tuple[float, float] | None]


def render_sweep(title: str, parameter: str, values: Sequence[object], ylabel: str,
                 lines: Sequence[SweepLine], reference: float | None) -> bytes:
    """A metric against the swept parameter: each seed as a dot beside its value, the mean as
    a line with its 95% CI as error bars; a categorical axis when the values are not all
    numbers."""
    import textwrap

    canvas, (ax,) = _canvas(1, width=6.8)
    numeric = all(isinstance(v, int | float) and not isinstance(v, bool) for v in values)
    x = np.array([float(v) for v in values]) if numeric else np.arange(len(values), dtype=float)
    span = (x.max() - x.min()) if numeric and len(x) > 1 else 1.0
    offsets = np.linspace(-0.03, 0.03, len(lines)) if len(lines) > 1 else np.zeros(1)
    for number, (line, offset) in enumerate(zip(lines, offsets, strict=True)):
        shifted = x + offset * span
        mean = np.array([np.nan if m is None else m for m in line.means])
        low = np.array([np.nan if i is None else i[0] for i in line.intervals])
        high = np.array([np.nan if i is None else i[1] for i in line.intervals])
        drawn = ax.errorbar(shifted, mean, yerr=[mean - low, high - mean], marker="o",
                            capsize=4, label=f"{line.label}: mean, 95% CI")
        colour = drawn.lines[0].get_color()
        for index, (position, seeds) in enumerate(zip(shifted, line.points, strict=True)):
            spread = np.linspace(0.015, 0.035, len(seeds)) * span if len(seeds) else []
            ax.scatter(position + spread, seeds, s=16, alpha=0.6, color=colour,
                       linewidths=0, label="each seed" if number == index == 0 else None)
    if reference is not None:
        ax.axhline(reference, linewidth=1.2, label="thesis / literature",
                   **REFERENCE_STYLES[0])
    if not numeric:
        ax.set_xticks(x, [str(v) for v in values])
    ax.set_xlabel(parameter)
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    ax.legend(fontsize="small")
    canvas.suptitle(textwrap.fill(title, 70), fontsize="medium")
    return _png(canvas)
