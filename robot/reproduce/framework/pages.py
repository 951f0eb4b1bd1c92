"""The markdown a reproduction or a sweep writes: what was run, every metric's mean with its
sample sd and 95% CI beside the reference, every claim with its test and verdict in words,
the study's notes and listings, the figures, the parameters as run, and the provenance."""

from __future__ import annotations

from collections.abc import Sequence

from robot.reproduce.framework.documents import ReproductionDocument, SeedRecord, SweepDocument
from robot.reproduce.framework.provenance import Provenance
from robot.reproduce.framework.settings import format_value
from robot.reproduce.framework.statistics import (
    ALPHA,
    BOOTSTRAP_RESAMPLES,
    Comparison,
    MetricSummary,
    Summary,
    number,
    p_text,
    reading,
)
from robot.reproduce.framework.study import Study, StudyConfig

STATISTICS_NOTE = (
    "Means are over the seeds that have a value (*seeds*); ± is the sample standard deviation "
    f"(ddof = 1); the CI is the 95% percentile bootstrap of the mean ({BOOTSTRAP_RESAMPLES:,} "
    "seeded resamples). Each claim is tested with a sign-flip permutation test over the seeds "
    f"(exact up to 16 seeds) at α = {ALPHA:g}; the effect size is the matched-pairs "
    "rank-biserial correlation r.")


def markdown_table(headers: Sequence[str], rows: Sequence[Sequence[object]]) -> str:
    """A Markdown table; cells as ``str`` gives them, a ``|`` inside a cell escaped."""
    def line(cells: Sequence[object]) -> str:
        return "| " + " | ".join(str(cell).replace("|", "\\|") for cell in cells) + " |"
    return "\n".join([line(headers), "|" + "---|" * len(headers)] + [line(r) for r in rows])


def spread_text(row: MetricSummary) -> str:
    """``mean ± sd`` with the sd to two significant digits."""
    if row.mean is None or row.sd is None:
        return number(row.mean)
    spread = number(row.sd) if abs(row.sd) >= 100 else f"{row.sd:.2g}"
    return f"{number(row.mean)} ± {spread}"


def interval_text(interval: tuple[float, float] | None) -> str:
    return "—" if interval is None else f"[{number(interval[0])}, {number(interval[1])}]"


def gap_text(row: MetricSummary) -> str:
    """mean - reference, signed, with the gap relative to the reference."""
    gap = row.gap
    if gap is None:
        return "—"
    text = ("+" if gap >= 0 else "-") + number(abs(gap))
    if row.reference:
        text += f" ({100 * gap / abs(row.reference):+.0f}%)"
    return text


def metric_rows(summary: Summary) -> list[list[str]]:
    """The measured table's rows (also what ``goalagent reproduce`` prints)."""
    return [[row.label, spread_text(row), interval_text(row.ci), f"{row.n}/{row.seeds}",
             number(row.reference), gap_text(row), row.source or "—"]
            for row in summary.metrics]


METRIC_HEADERS = ("quantity", "mean ± sd", "95% CI", "seeds", "reference", "gap", "source")


def claims_text(comparisons: Sequence[Comparison]) -> str:
    """Each claim, its test and its verdict in words."""
    lines = ["## Claims and tests", ""]
    if not comparisons:
        return "\n".join(lines + ["This study makes no claim that compares seeds.", ""])
    for index, comparison in enumerate(comparisons, start=1):
        lines += [f"{index}. **Claim**: {comparison.claim}  ",
                  f"   **Test**: {comparison.test}.  ",
                  f"   **Verdict**: {reading(comparison)}", ""]
    return "\n".join(lines)


def seed_ranges(seeds: Sequence[int]) -> str:
    """``0–4, 7, 10–14``."""
    parts: list[str] = []
    ordered = sorted(seeds)
    start = previous = ordered[0]
    for seed in [*ordered[1:], None]:
        if seed is not None and seed == previous + 1:
            previous = seed
            continue
        parts.append(f"{start}" if start == previous else f"{start}–{previous}")
        if seed is not None:
            start = previous = seed
    return ", ".join(parts)


def parameters_text(study: Study, config: dict, grid: Sequence[str] = ()) -> str:
    """Every parameter as run, its default (the thesis's) where it differs, and its meaning."""
    defaults = study.default_config().model_dump(mode="json")
    rows = []
    for key, value in config.items():
        shown = "swept" if key in grid else format_value(value)
        if key not in grid and value != defaults[key]:
            shown = f"**{shown}** (default {format_value(defaults[key])})"
        rows.append([f"`{key}`", shown, study.config.describe(key)])
    return "\n".join(["## Parameters", "", markdown_table(["parameter", "value", "meaning"],
                                                          rows), ""])


def deviations_text(study: Study, config: dict, grid: Sequence[str] = ()) -> str:
    """Every open choice the config declares (a field with a ``Reading``): the thesis's text,
    the value as run and what the code does; then the study's fixed deviations."""
    defaults = study.default_config().model_dump(mode="json")
    lines = ["## Deviations and open choices", ""]
    rows = []
    for key, value in config.items():
        reading = study.config.reading(key)
        if reading is None:
            continue
        shown = "swept" if key in grid else format_value(value)
        if key not in grid and value != defaults[key]:
            shown = f"**{shown}** (default {format_value(defaults[key])})"
        rows.append([f"`{key}`", reading.thesis, shown, study.config.describe(key)])
    if rows:
        lines += ["Choices the thesis leaves open or that this code once read otherwise, each "
                  "a parameter (`--set`, `--grid`); the default is the thesis's reading where "
                  "it gives one.", "",
                  markdown_table(["parameter", "the thesis", "this run", "what the code does"],
                                 rows), ""]
    if study.deviations:
        lines += ["Fixed differences (no parameter):", ""]
        lines += [f"- **{item.topic}**. Thesis: {item.thesis} Here: {item.code}"
                  for item in study.deviations]
        lines.append("")
    if not rows and not study.deviations:
        lines += ["None declared.", ""]
    return "\n".join(lines)


def provenance_text(provenance: Sequence[Provenance], seeds: Sequence[SeedRecord]) -> str:
    """Which versions ran which seeds."""
    lines = ["## Provenance", ""]
    for index, record in enumerate(provenance):
        ran = [seed.seed for seed in seeds if seed.provenance == index]
        if not ran:
            continue
        commit = record.git_commit or "no git checkout"
        lines.append(
            f"- seeds {seed_ranges(ran)}: goalagent {record.goalagent} (commit {commit}), "
            f"Python {record.python}, MuJoCo {record.mujoco}, SWI-Prolog {record.swi_prolog}, "
            f"numpy {record.numpy}, scipy {record.scipy}, scikit-learn {record.scikit_learn}; "
            f"{record.platform}")
    return "\n".join(lines) + "\n"


def reproduction_page(study: Study, document: ReproductionDocument,
                      figure_files: Sequence[str], listings: str) -> str:
    """NAME.md."""
    seeds = [record.seed for record in document.seeds]
    lines = [f"# {study.name}", "", study.description, "",
             f"Produced by `{document.command}` ({len(seeds)} seeds: {seed_ranges(seeds)}).",
             "", "## Measured", "", markdown_table(METRIC_HEADERS,
                                                   metric_rows(document.summary)),
             "", STATISTICS_NOTE, "", claims_text(document.summary.comparisons)]
    if study.notes:
        lines += ["## Setup and reading", "", study.notes.strip(), ""]
    lines.append(deviations_text(study, document.config))
    if listings.strip():
        lines += [listings.strip(), ""]
    for name in figure_files:
        lines += [f"![{name}]({name})", ""]
    lines += [parameters_text(study, document.config),
              provenance_text(document.provenance, document.seeds)]
    return "\n".join(lines)


def cell_label(values: dict) -> str:
    return ", ".join(f"{key} = {format_value(value)}" for key, value in values.items())


HOLDS = ("supported", "not contradicted")
"""Verdicts under which a claim holds: a directed one's test rejects in its favour, or a claim
of sameness is not rejected."""


def verdict_summary(document: SweepDocument, index: int) -> str:
    """Which cells make claim ``index`` hold (supported, or not contradicted for a claim of
    sameness) and which do not, each with p and r; the holding cells first."""
    groups: dict[str, list[str]] = {}
    for cell in document.cells:
        comparison = cell.summary.comparisons[index]
        shown = cell_label(cell.values)
        if comparison.p_value is not None:
            shown += f" (p = {p_text(comparison.p_value)}"
            if comparison.effect_size is not None:
                shown += f", r = {comparison.effect_size:+.2f}"
            shown += ")"
        groups.setdefault(comparison.verdict, []).append(shown)
    order = sorted(groups, key=lambda verdict: (verdict not in HOLDS, verdict))
    parts = [f"{verdict} in {len(groups[verdict])} of {len(document.cells)} cells: "
             f"{'; '.join(groups[verdict])}" for verdict in order]
    return "By cell: " + ". ".join(parts) + "."


def verdicts_text(document: SweepDocument) -> list[str]:
    """The sweep's verdict: for each claim, the cells that make it hold and those that do not,
    from the paired tests below."""
    claims = document.cells[0].summary.comparisons
    if not claims:
        return []
    lines = ["## Verdicts: which settings make each claim hold", "",
             "A claim holds in a cell when its paired test supports it (a claim of sameness: "
             "when the test does not contradict it); p is the test's, r the rank-biserial "
             "effect size (tables under *Claims per cell*).", ""]
    for index, claim in enumerate(claims):
        lines += [f"{index + 1}. {claim.claim}. {verdict_summary(document, index)}", ""]
    return lines


def sweep_page(study: Study, document: SweepDocument, headline: Sequence[str],
               plot_files: Sequence[str], base_config: StudyConfig) -> str:
    """NAME-sweep-KEYS.md: the headline metrics per cell, each claim's verdict per cell."""
    keys = list(document.grid)
    seeds = [record.seed for record in document.cells[0].seeds]
    lines = [f"# {study.name}: sweep over {', '.join(keys)}", "", study.description, "",
             f"Produced by `{document.command}` ({len(document.cells)} cells, {len(seeds)} "
             f"seeds each: {seed_ranges(seeds)}).", ""]
    if len(seeds) < study.default_seeds:
        full = document.command.replace(f"--seeds {len(seeds)}",
                                        f"--seeds {study.default_seeds}")
        lines += [f"**Reduced size**: {len(seeds)} seeds per cell, against the study's "
                  f"{study.default_seeds}, to fit the shared machine; the full sweep is "
                  f"`{full}`.", ""]
    lines += ["## Headline metrics per cell", ""]
    rows = []
    for cell in document.cells:
        by_key = {row.key: row for row in cell.summary.metrics}
        rows.append([*(format_value(cell.values[key]) for key in keys),
                     *(f"{spread_text(by_key[m])} {interval_text(by_key[m].ci)} "
                       f"({by_key[m].n}/{by_key[m].seeds})" for m in headline)])
    labels = [next(r.label for r in document.cells[0].summary.metrics if r.key == m)
              for m in headline]
    lines += [markdown_table([*keys, *labels], rows), "", STATISTICS_NOTE, ""]
    lines += verdicts_text(document)
    lines += ["## Claims per cell", ""]
    claims = document.cells[0].summary.comparisons
    if not claims:
        lines += ["This study makes no claim that compares seeds.", ""]
    for index, claim in enumerate(claims):
        lines += [f"{index + 1}. {claim.claim}", ""]
        table = []
        for cell in document.cells:
            comparison = cell.summary.comparisons[index]
            table.append([*(format_value(cell.values[key]) for key in keys),
                          comparison.verdict, number(comparison.mean_difference),
                          interval_text(comparison.ci),
                          "—" if comparison.p_value is None else p_text(comparison.p_value),
                          "—" if comparison.effect_size is None
                          else f"{comparison.effect_size:+.2f}"])
        lines += [markdown_table([*keys, "verdict", "mean difference", "95% CI", "p", "r"],
                                 table), ""]
    for name in plot_files:
        lines += [f"![{name}]({name})", ""]
    all_seeds = [record for cell in document.cells for record in cell.seeds]
    lines.append(deviations_text(study, base_config.model_dump(mode="json"), keys))
    lines += [parameters_text(study, base_config.model_dump(mode="json"), keys),
              provenance_text(document.provenance, all_seeds)]
    return "\n".join(lines)
