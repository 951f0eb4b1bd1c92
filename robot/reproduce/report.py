"""A reproduction's outputs: the markdown page (its table of measured values beside the
reference with the gap) and its figures (mean ± standard deviation over seeds, references as
dashed lines)."""

from __future__ import annotations

import io
import math
from collections.abc import Sequence

import numpy as np

from robot.reproduce.framework import Comparison, Figure, Reproduction, markdown_table

REFERENCE_STYLES = ({"linestyle": "--", "color": "0.25"}, {"linestyle": ":", "color": "firebrick"},
                    {"linestyle": "-.", "color": "darkgreen"})
"""How reference lines look, in the order a panel lists them."""


def number(value: float | None) -> str:
    """Four significant digits (whole thousands grouped); an em dash for a missing value."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "—"
    if abs(value) >= 1000:
        return f"{value:,.0f}"
    return f"{value:.4g}"


def measured_text(row: Comparison) -> str:
    """The measured value with its spread over seeds to two significant digits, e.g. ``2.1 ±
    0.31``."""
    if row.spread is None or row.measured is None:
        return number(row.measured)
    spread = number(row.spread) if abs(row.spread) >= 100 else f"{row.spread:.2g}"
    return f"{number(row.measured)} ± {spread}"


def gap_text(row: Comparison) -> str:
    """measured - reference, signed, with the gap relative to the reference."""
    gap = row.gap
    if gap is None:
        return "—"
    text = ("+" if gap >= 0 else "-") + number(abs(gap))
    if row.reference:
        text += f" ({100 * gap / abs(row.reference):+.0f}%)"
    return text


def markdown(reproduction: Reproduction, comparisons: Sequence[Comparison],
             figure_files: Sequence[str], n_seeds: int, scale: float, command: str,
             listings: str = "") -> str:
    """NAME.md: title, command, the comparison table, notes, listings and the figures."""
    lines = [f"# {reproduction.name}", "", reproduction.description, "",
             f"Produced by `{command}` ({n_seeds} seeds"
             + ("" if scale == 1.0 else f", scale {scale:g} of the full run") + ").", "",
             markdown_table(
                 ["quantity", f"measured (mean ± sd over {n_seeds} seeds)", "reference", "gap",
                  "source"],
                 [[row.quantity, measured_text(row), number(row.reference), gap_text(row),
                   row.source or "—"] for row in comparisons])]
    if reproduction.notes:
        lines += ["", reproduction.notes.strip()]
    if listings.strip():
        lines += ["", listings.strip()]
    for name in figure_files:
        lines += ["", f"![{name}]({name})"]
    return "\n".join(lines) + "\n"


def render_figure(figure: Figure, n_seeds: int) -> bytes:
    """The figure as PNG bytes: each series' mean over seeds with a ±1 sd band."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure as Canvas

    canvas = Canvas(figsize=(5.2 * len(figure.panels), 3.8), layout="constrained")
    FigureCanvasAgg(canvas)
    axes = canvas.subplots(1, len(figure.panels), squeeze=False)[0]
    for ax, panel in zip(axes, figure.panels, strict=True):
        for series in panel.series:
            runs = np.asarray(series.runs, dtype=float)
            if runs.ndim != 2 or runs.shape[1] != len(series.x):
                raise ValueError(f"figure {figure.stem}: series {series.label!r} needs one run "
                                 f"of {len(series.x)} values per seed")
            mean, spread = np.nanmean(runs, axis=0), np.nanstd(runs, axis=0)
            line, = ax.plot(series.x, mean, label=f"{series.label} (mean ± sd, {n_seeds} seeds)")
            ax.fill_between(series.x, mean - spread, mean + spread, alpha=0.25,
                            color=line.get_color(), linewidth=0)
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
    buffer = io.BytesIO()
    canvas.savefig(buffer, format="png", dpi=110)
    return buffer.getvalue()
