"""The research workbench's framework on a toy study of its own: typed settings, the runner
and its cache (resume, corrupt entries, failures, interrupts), the statistics on hand-computed
numbers, merge, replot and sweeps, and what the pages and plots hold."""

from __future__ import annotations

import json
import os
import platform
import re
from importlib import metadata
from pathlib import Path

import numpy as np
import pytest
from matplotlib.colors import to_rgb
from matplotlib.image import imread
from rich.console import Console

from robot.reproduce.framework import Claim
from robot.reproduce.framework.backends import LocalBackend
from robot.reproduce.framework.cache import Cache
from robot.reproduce.framework.documents import DocumentError, read
from robot.reproduce.framework.runner import command_line, merge, replot, reproduce
from robot.reproduce.framework.settings import SettingError, apply, parse_grid
from robot.reproduce.framework.statistics import (
    mean_interval,
    rank_biserial,
    reading,
    sign_flip_p,
    sign_flip_ps,
    summarize,
)
from robot.reproduce.framework.sweeps import replot as replot_sweeps
from robot.reproduce.framework.sweeps import sweep
from robot.reproduce.framework.tasks import ReproductionFailed
from tests.conftest import ROOT
from tests.robot.reproduce.toy_study import TOY, ToyConfig, ToyResult, toy_metrics

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)


def run_toy(out: Path, seeds=range(3), cache: Path | None = None, jobs: int = 1, **values):
    return reproduce(TOY, ToyConfig(**values), list(seeds), LocalBackend(jobs), out,
                     cache=Cache(cache) if cache else None)


def without_seconds(document) -> dict:
    data = document.model_dump(mode="json")
    for record in data.get("seeds", []):
        record.pop("seconds")
    return data


# -- settings ----------------------------------------------------------------------------------

def test_set_reads_each_value_as_its_field_type():
    config = apply(TOY, ToyConfig(), ["offset=1e-4", "choice=doubled", "fail_seed=null",
                                      "cans=[\"o1\", \"o3\"]", "steps=7", "log=400"])
    assert config.offset == 1e-4 and config.choice == "doubled" and config.fail_seed is None
    assert config.cans == ("o1", "o3") and config.steps == 7 and config.log == "400"
    assert apply(TOY, config, ["fail_seed=2", "fail_seed=3"]).fail_seed == 3  # later wins


@pytest.mark.parametrize(("setting", "message"), [
    ("ofset=1", "toy-run has no parameter 'ofset'; did you mean 'offset'?"),
    ("STEPS=2", "did you mean 'steps'?"),
    ("steps=2.5", "steps=2.5: steps: Input should be a valid integer"),
    ("steps=0", "steps: Input should be greater than or equal to 1"),
    ("choice=tripled", "Input should be 'plain' or 'doubled'"),
    ("scale=2", "scale: Input should be less than or equal to 1"),
    ("offset", "--set 'offset': write KEY=VALUE"),
])
def test_a_bad_setting_is_one_clear_error(setting, message):
    with pytest.raises(SettingError, match=None) as error:
        apply(TOY, ToyConfig(), [setting])
    assert message in str(error.value) and "\n" not in str(error.value)


def test_grid_values_are_typed_and_checked():
    assert parse_grid(TOY, ToyConfig(), ["offset=0,0.5", "cans=[\"o1\",\"o2\"],[\"o3\"]"]) == {
        "offset": [0.0, 0.5], "cans": [("o1", "o2"), ("o3",)]}
    for items, message in ((["offset="], "none may be empty"), ([], "at least one --grid"),
                           (["offset=1,1.0"], "given twice"),
                           (["offset=1", "offset=2"], "given twice"),
                           (["steps=1,0"], "greater than or equal to 1")):
        with pytest.raises(SettingError, match=message):
            parse_grid(TOY, ToyConfig(), items)


def test_the_command_line_records_every_value_not_the_default():
    config = apply(TOY, ToyConfig(), ["offset=0.5", "cans=[\"o2\"]"])
    assert command_line(TOY, config, [3, 4]) == (
        "goalagent reproduce toy-run --seeds 2 --seed-offset 3 --set offset=0.5 "
        "--set 'cans=[\"o2\"]'")
    assert command_line(TOY, config, [0, 1, 5]) == (
        "goalagent reproduce toy-run --seeds 2 --set offset=0.5 --set 'cans=[\"o2\"]'; "
        "goalagent reproduce toy-run --seeds 1 --seed-offset 5 --set offset=0.5 "
        "--set 'cans=[\"o2\"]'")


# -- statistics, on numbers worked out by hand ---------------------------------------------------

def test_means_carry_the_sample_sd_and_a_reproducible_bootstrap_ci():
    seeds = [ToyResult(value=v, curve=[], reached=None) for v in (1.0, 2.0, 3.0, 4.0)]
    summary = summarize(toy_metrics(ToyConfig()), [], seeds)
    value = summary.metrics[0]
    assert value.mean == 2.5 and value.sd == pytest.approx(1.2909944)  # ddof = 1
    assert 1.0 <= value.ci[0] < 2.5 < value.ci[1] <= 4.0
    assert summarize(toy_metrics(ToyConfig()), [], seeds).metrics[0].ci == value.ci
    assert value.gap == 0.5 and value.n == value.seeds == 4
    reached = summary.metrics[1]
    assert (reached.n, reached.mean, reached.sd, reached.ci) == (0, None, None, None)
    assert mean_interval(np.array([3.0]), "x") is None
    assert mean_interval(np.array([3.0, 3.0]), "x") == (3.0, 3.0)


def test_the_sign_flip_test_is_exact_and_the_effect_size_is_the_rank_biserial_r():
    assert sign_flip_p(np.array([1.0, 2.0, 3.0]), "greater", "a") == pytest.approx(1 / 8)
    assert sign_flip_p(np.ones(5), "greater", "a") == pytest.approx(1 / 32)
    assert sign_flip_p(np.ones(5), "same", "a") == pytest.approx(2 / 32)
    assert sign_flip_p(np.ones(5), "less", "a") == 1.0
    assert sign_flip_p(np.zeros(4), "greater", "a") == 1.0
    assert sign_flip_p(np.array([2.0]), "greater", "a") == 0.5
    assert sign_flip_p(np.array([2.0]), "less", "a") == 1.0
    assert rank_biserial(np.array([1.0, -2.0, 3.0])) == pytest.approx((4 - 2) / 6)
    assert rank_biserial(np.array([0.0, 0.0])) == 0.0


@pytest.mark.parametrize("differences", [
    np.array([1.0, 2.0, 3.0]), np.array([0.3, -0.1, 0.2, -0.2, 0.1, 0.0, 0.4]),
    np.array([1.0, -1.0, 2.0, -2.0]),  # ties with the observed mean among the patterns
    np.round(np.random.default_rng(3).normal(size=17), 1),  # 2^17 > PERMUTATIONS: drawn
])
@pytest.mark.parametrize("direction", ["greater", "less"])
def test_the_opposite_p_value_counted_on_the_null_is_scipys_own_test(differences, direction):
    """sign_flip_ps counts the opposite direction's p-value on the null distribution of the
    claim's own test instead of running a second test: what a second test gives."""
    opposite = {"greater": "less", "less": "greater"}[direction]
    assert sign_flip_ps(differences, direction, "claim") == (
        sign_flip_p(differences, direction, "claim"),
        sign_flip_p(differences, opposite, "claim"))


@pytest.mark.parametrize(("values", "claim", "verdict", "p"), [
    ([1.0] * 5, Claim("up", "value", 0.0, "greater"), "supported", 1 / 32),
    ([-1.0] * 5, Claim("up", "value", 0.0, "greater"), "contradicted", 1.0),
    # ±1 ±1 ±2 ±2 >= 0 in 10 of 16 sign patterns (6 above zero, 4 at it)
    ([1.0, -1.0, 2.0, -2.0], Claim("up", "value", 0.0, "greater"), "not supported", 10 / 16),
    ([1.0] * 5, Claim("equal", "value", 1.0, "same"), "not contradicted", 1.0),
    ([1.0] * 5, Claim("equal", "value", 0.0, "same"), "not contradicted", 2 / 32),
    ([1.0] * 6, Claim("equal", "value", 0.0, "same"), "contradicted", 2 / 64),
    ([1.0] * 4, Claim("paired", "shifted", "value", "greater"), "not supported", 1 / 16),
])
def test_each_claim_gets_a_verdict(values, claim, verdict, p):
    seeds = [ToyResult(value=v, curve=[], reached=None) for v in values]
    (comparison,) = summarize(toy_metrics(ToyConfig()), [claim], seeds).comparisons
    assert (comparison.verdict, comparison.n) == (verdict, len(values))
    assert comparison.p_value == pytest.approx(p)
    assert "exact over all" in comparison.test
    if verdict == "contradicted" and claim.direction != "same":
        assert comparison.p_opposite == pytest.approx(1 / 32)
        assert "(the opposite one-sided test: p = 0.031)" in reading(comparison)


def test_a_claim_on_values_no_seed_has_is_not_tested():
    seeds = [ToyResult(value=1.0, curve=[], reached=None)] * 3
    (comparison,) = summarize(toy_metrics(ToyConfig()), [Claim("x", "reached", 0.0)],
                              seeds).comparisons
    assert comparison.verdict == "not tested" and comparison.p_value is None


# -- the runner and its cache ------------------------------------------------------------------

def test_a_run_writes_typed_json_a_page_and_figures(tmp_path):
    outcome = run_toy(tmp_path, offset=0.5)
    document = json.loads((tmp_path / "toy-run.json").read_text())
    assert document["schema_version"] == 2 and document["kind"] == "reproduction"
    assert document["config"]["offset"] == 0.5
    assert document["command"] == "goalagent reproduce toy-run --seeds 3 --set offset=0.5"
    assert [s["result"]["value"] for s in document["seeds"]] == [0.5, 1.5, 4.5]
    provenance = document["provenance"][0]  # this process's versions, as it reports them
    assert provenance["python"] == platform.python_version()
    assert provenance["platform"] == platform.platform()
    assert provenance["goalagent"] == metadata.version("goalagent")
    assert provenance["mujoco"] == metadata.version("mujoco")
    assert re.fullmatch(r"\d+\.\d+\.\d+", provenance["swi_prolog"])
    assert (provenance["git_commit"] is None if not (ROOT / ".git").exists()
            else re.fullmatch(r"[0-9a-f]{40}(\+dirty)?", provenance["git_commit"]))
    assert all(s["seconds"] >= 0 and s["provenance"] == 0 for s in document["seeds"])
    value = document["summary"]["metrics"][0]
    assert value["mean"] == pytest.approx(6.5 / 3) and value["sd"] == pytest.approx(2.0816660)
    assert [c["verdict"] for c in document["summary"]["comparisons"]] == [
        "not supported", "not supported"]  # three seeds: p = 1/8 at best
    assert sorted(path.name for path in outcome.files) == [
        "toy-run-curve.png", "toy-run.json", "toy-run.md"]
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]  # no temporary left
    umask = os.umask(0)
    os.umask(umask)
    assert {p.stat().st_mode & 0o777 for p in outcome.files} == {0o666 & ~umask}


def test_the_page_states_claims_tests_verdicts_parameters_and_provenance(tmp_path):
    run_toy(tmp_path, seeds=range(5), offset=1.0)
    page = (tmp_path / "toy-run.md").read_text()
    assert "| the value | 7 ± 6.6 | [" in page and "| 5/5 | 2 | +5 (+250%) | by hand |" in page
    assert "| where odd seeds got | 2 ± 1.4 | [1, 3] | 2/5 |" in page
    assert ("1. **Claim**: values grow beyond zero  \n   **Test**: sign-flip permutation test "
            "of the mean difference, each seed against 0, one-sided (greater), exact over all "
            "32 sign patterns, n = 5.  \n   **Verdict**: **supported** at α = 0.05") in page
    assert "p = 0.031" in page and "rank-biserial r = +1.00" in page
    assert "| `offset` | **1.0** (default 0.0) | Added to every value. |" in page
    assert "| `steps` | 3 | A parameter with a limit. |" in page
    assert "## Provenance\n\n- seeds 0–4: goalagent " in page
    assert "![toy-run-curve.png](toy-run-curve.png)" in page


def test_figures_show_the_mean_and_its_ci_band(tmp_path):
    from matplotlib.image import imread

    run_toy(tmp_path)
    image = imread(tmp_path / "toy-run-curve.png")
    assert image.shape[:2] == (418, 572)  # 5.2 x 3.8 inches at 110 dpi, one panel
    assert image[..., :3].std() > 0.05  # drawn on, not a blank canvas
    pale = np.all(image[..., :3] > 0.6, axis=-1) & (image[..., 2] - image[..., 0] > 0.1)
    assert pale.sum() > 500  # the translucent blue CI band


def test_a_second_run_takes_every_seed_from_the_cache(tmp_path):
    log = tmp_path / "ran.txt"
    first = run_toy(tmp_path / "a", cache=tmp_path / "cache", log=str(log))
    again = run_toy(tmp_path / "b", cache=tmp_path / "cache", log=str(log))
    assert log.read_text().split() == ["0", "1", "2"]
    assert (again.tally.computed, again.tally.cached) == (0, 3)
    assert again.document == first.document
    other = run_toy(tmp_path / "c", cache=tmp_path / "cache", log=str(log), offset=1.0)
    assert other.tally.computed == 3  # another config: another key


def test_a_corrupt_cache_entry_is_reported_with_its_path_and_run_again(tmp_path):
    log, cache = tmp_path / "ran.txt", tmp_path / "cache"
    first = run_toy(tmp_path / "a", cache=cache, log=str(log))
    entries = sorted((cache / "toy-run").glob("*-seed1.json"))
    entries[0].write_text('{"schema_version": 2, "result": ')
    seed2 = sorted((cache / "toy-run").glob("*-seed2.json"))[0]
    seed2.write_text(seed2.read_text().replace('"value": 4.0', '"value": "four"'))
    console = Console(record=True, width=300)
    again = reproduce(TOY, ToyConfig(log=str(log)), [0, 1, 2], LocalBackend(1), tmp_path / "b",
                      cache=Cache(cache), console=console)
    text = console.export_text()
    assert f"corrupt cache entry {entries[0]}: not JSON" in text
    assert f"corrupt cache entry {seed2}: value: Input should be a valid number" in text
    assert log.read_text().split() == ["0", "1", "2", "1", "2"]
    assert (again.tally.computed, again.tally.cached, again.tally.recomputed_corrupt) == (2, 1, 2)
    assert without_seconds(again.document) == without_seconds(first.document)
    assert json.loads(entries[0].read_text())["result"]["value"] == 1.0  # repaired


def test_a_seed_cached_by_other_code_is_run_again(tmp_path):
    """Each entry carries the fingerprint of the code's files; an entry written by code
    that has changed since (here: another fingerprint, as an edit to a study would give)
    is not this code's result."""
    log, cache = tmp_path / "ran.txt", tmp_path / "cache"
    first = run_toy(tmp_path / "a", cache=cache, log=str(log))
    seed1 = sorted((cache / "toy-run").glob("*-seed1.json"))[0]
    entry = json.loads(seed1.read_text())
    assert re.fullmatch(r"[0-9a-f]{64}", entry["code"])
    seed1.write_text(json.dumps({**entry, "code": "0" * 64}))
    console = Console(record=True, width=300)
    again = reproduce(TOY, ToyConfig(log=str(log)), [0, 1, 2], LocalBackend(1), tmp_path / "b",
                      cache=Cache(cache), console=console)
    assert "1 cached seed of this config came from code that has changed since" in (
        console.export_text())
    assert log.read_text().split() == ["0", "1", "2", "1"]
    assert (again.tally.computed, again.tally.cached, again.tally.recomputed_stale) == (1, 2, 1)
    assert without_seconds(again.document) == without_seconds(first.document)
    assert json.loads(seed1.read_text())["code"] == entry["code"]  # rewritten by this code


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_failing_seed_is_named_and_the_seeds_before_it_stay_cached(tmp_path, jobs):
    log, cache = tmp_path / "ran.txt", tmp_path / "cache"
    with pytest.raises(ReproductionFailed, match="toy-run: seed 1 failed: ArithmeticError: no"):
        run_toy(tmp_path / "out", cache=cache, jobs=jobs, fail_seed=1, log=str(log))
    assert not (tmp_path / "out").exists()
    if jobs == 1:
        assert len(list((cache / "toy-run").glob("*-seed0.json"))) == 1


def test_an_interrupted_run_resumes_without_running_a_finished_seed_again(tmp_path):
    log, cache = tmp_path / "ran.txt", tmp_path / "cache"
    with pytest.raises(KeyboardInterrupt):
        run_toy(tmp_path / "out", seeds=range(4), cache=cache, log=str(log), interrupt_seed=2)
    assert log.read_text().split() == ["0", "1", "2"]
    config = ToyConfig(log=str(log), interrupt_seed=2)
    resumed = reproduce(TOY, config.model_copy(update={"interrupt_seed": None}), [0, 1],
                        LocalBackend(1), tmp_path / "out", cache=Cache(cache))
    assert resumed.tally.computed == 2  # interrupt_seed is part of the config: another key
    finished = reproduce(TOY, config, [0, 1, 3], LocalBackend(1), tmp_path / "out",
                         cache=Cache(cache))
    assert (finished.tally.cached, finished.tally.computed) == (2, 1)
    assert log.read_text().split() == ["0", "1", "2", "0", "1", "3"]


def test_parallel_processes_give_the_same_document_but_for_the_seconds(tmp_path):
    alone = run_toy(tmp_path / "one", jobs=1, scale=0.5)
    parallel = run_toy(tmp_path / "two", jobs=2, scale=0.5)
    assert without_seconds(parallel.document) == without_seconds(alone.document)


# -- replot, merge, sweeps ------------------------------------------------------------------------

def test_replot_redraws_everything_from_the_json_byte_for_byte(tmp_path):
    outcome = run_toy(tmp_path)
    before = {path.name: path.read_bytes() for path in outcome.files}
    (tmp_path / "toy-run.md").unlink()
    replot(TOY, tmp_path)
    assert {path.name: path.read_bytes() for path in outcome.files} == before
    (tmp_path / "toy-run.json").write_text(json.dumps({"summary": {}, "seeds": []}))
    with pytest.raises(DocumentError, match="schema version 1, this goalagent reads version 2"):
        replot(TOY, tmp_path)


def test_shards_merge_into_the_document_of_one_run(tmp_path):
    whole = run_toy(tmp_path / "whole", seeds=range(4))
    run_toy(tmp_path / "a", seeds=range(2))
    run_toy(tmp_path / "b", seeds=range(1, 4))  # seed 1 in both shards
    merged = merge(TOY, [tmp_path / "a" / "toy-run.json", tmp_path / "b" / "toy-run.json"],
                   tmp_path / "merged")
    assert without_seconds(merged.document) == without_seconds(whole.document)
    run_toy(tmp_path / "c", seeds=range(2), offset=1.0)
    with pytest.raises(DocumentError, match="another config"):
        merge(TOY, [tmp_path / "a" / "toy-run.json", tmp_path / "c" / "toy-run.json"],
              tmp_path / "merged")


def test_a_sweep_runs_one_cell_per_combination_with_statistics_and_plots(tmp_path):
    log = tmp_path / "ran.txt"
    grid = parse_grid(TOY, ToyConfig(), ["offset=0,1,2", "choice=plain,doubled"])
    # in this process: a sweep's cells in worker processes are test_workbench_cli.py's sweep
    # (--jobs 2), and processes giving the same document is tested above
    outcome = sweep(TOY, ToyConfig(log=str(log)), grid, [0, 1, 2], LocalBackend(1),
                    tmp_path, cache=Cache(tmp_path / "cache"))
    document = read(tmp_path / "toy-run-sweep-offset-choice.json")
    assert [cell.values for cell in document.cells] == [
        {"offset": o, "choice": c} for o in (0.0, 1.0, 2.0) for c in ("plain", "doubled")]
    doubled = document.cells[3].summary.metrics[0]  # offset 1, doubled: 2, 4, 10
    assert doubled.mean == pytest.approx(16 / 3) and doubled.ci is not None
    assert len(log.read_text().split()) == 18 and outcome.tally.computed == 18
    page = (tmp_path / "toy-run-sweep-offset-choice.md").read_text()
    assert "| offset | choice | the value |" in page
    assert "| 1.0 | doubled | 5.333 ± 4.2 [" in page and "(3/3) |" in page
    assert "1. values grow beyond zero" in page and "| 2.0 | doubled | not supported |" in page
    plot = imread(tmp_path / "toy-run-sweep-offset-choice-value.png")
    assert plot.shape[:2] == (418, 748)  # one 6.8 x 3.8 inch panel at 110 dpi
    series = [colour for colour in ("C0", "C1")  # one line per choice, in the colour cycle's order
              if np.all(np.abs(plot[..., :3] - to_rgb(colour)) < 0.02, axis=-1).sum() > 20]
    assert series == ["C0", "C1"]
    before = (tmp_path / "toy-run-sweep-offset-choice.md").read_bytes()
    replot_sweeps(TOY, tmp_path)
    assert (tmp_path / "toy-run-sweep-offset-choice.md").read_bytes() == before
    again = sweep(TOY, ToyConfig(log=str(log)), grid, [0, 1, 2], LocalBackend(1), tmp_path,
                  cache=Cache(tmp_path / "cache"))
    assert (again.tally.computed, again.tally.cached) == (0, 18)  # resumed: nothing run


def test_a_verdict_says_when_no_outcome_could_have_reached_alpha():
    seeds = [ToyResult(value=39.0, curve=[], reached=None)] * 5
    (same,) = summarize(toy_metrics(ToyConfig()), [Claim("36", "value", 36.0, "same")],
                        seeds).comparisons
    assert same.verdict == "not contradicted" and same.smallest_p == 2 / 32
    assert ("with these 5 seeds no outcome could reach α: the smallest possible p is 0.062"
            in reading(same))
    (up,) = summarize(toy_metrics(ToyConfig()), [Claim("up", "value", 36.0)], seeds).comparisons
    assert up.verdict == "supported" and up.smallest_p == 1 / 32
    assert "no outcome could reach" not in reading(up)
