"""The `goalagent reproduce` framework: every registered reproduction at its quick size, the
runner (parallel seeds, failures named by seed, atomic outputs), the markdown table and the
command line."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from robot.reproduce.framework import (
    Comparison,
    Figure,
    Panel,
    Reference,
    Reproduction,
    Series,
    find,
    registered,
)
from robot.reproduce.report import markdown
from robot.reproduce.runner import ReproductionFailed, replot, run

ROOT = Path(__file__).resolve().parents[1]
SUMMARY_KEYS = {
    "xcs-mux": {"mux6": {"final_accuracy", "problems_to_99"},
                "mux11": {"final_accuracy", "problems_to_99"}},
    "xcs-woods2": {"final_steps", "optimum"},
    "appA-params": {"woods2": {"final_steps"}, "mux6": {"final_accuracy"}},
    "xcs-maze4": {"generalising": {"final_steps", "optimum"}, "specific": {"final_steps"}},
}


def test_the_xcs_reproductions_are_registered_by_name():
    names = [reproduction.name for reproduction in registered()]
    assert {"xcs-mux", "xcs-woods2", "appA-params", "xcs-maze4"} <= set(names)
    assert find("xcs-woods2").name == "xcs-woods2"


@pytest.mark.parametrize("name", sorted(SUMMARY_KEYS))
def test_each_reproduction_runs_small_and_writes_json_markdown_and_figures(tmp_path, name):
    reproduction = find(name)
    outcome = run(reproduction, seeds=2, scale=reproduction.quick_scale, jobs=1, out=tmp_path,
                  command=f"test {name}")
    document = json.loads((tmp_path / f"{name}.json").read_text())
    assert set(document) >= {"summary", "seeds"} and len(document["seeds"]) == 2
    expected = SUMMARY_KEYS[name]
    if isinstance(expected, dict):
        for part, keys in expected.items():
            assert keys <= set(document["summary"][part])
    else:
        assert expected <= set(document["summary"])
    page = (tmp_path / f"{name}.md").read_text()
    assert "| quantity |" in page and f"test {name}" in page
    pngs = sorted(tmp_path.glob(f"{name}-*.png"))
    assert pngs and all(p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" for p in pngs)
    assert all(f"]({p.name})" in page for p in pngs)
    assert sorted(outcome.files) == sorted([*pngs, tmp_path / f"{name}.md",
                                            tmp_path / f"{name}.json"])
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]  # no temporary left
    umask = os.umask(0)
    os.umask(umask)
    assert {p.stat().st_mode & 0o777 for p in outcome.files} == {0o666 & ~umask}


# -- the runner, on a tiny reproduction of its own ---------------------------------------------

def _square_seed(seed: int, scale: float, progress) -> dict:
    for step in range(4):
        progress(step / 4)
    return {"seed": seed, "value": seed * seed * scale, "curve": [seed, seed + 1.0]}


def _failing_seed(seed: int, scale: float, progress) -> dict:
    if seed == 1:
        raise ArithmeticError("no luck")
    return {"seed": seed}


def _not_json_seed(seed: int, scale: float, progress) -> dict:
    return {"value": float("nan")}


def _summary(seeds: list[dict]) -> dict:
    return {"total": sum(seed.get("value", 0) for seed in seeds)}


def _rows(summary: dict, seeds: list[dict]) -> list[Comparison]:
    return [Comparison("total", summary["total"], None, 2.0, "by hand")]


def _plots(seeds: list[dict]) -> list[Figure]:
    return [Figure("curve", "A curve", [Panel("x", "y", [
        Series("seed curve", [0.0, 1.0], [seed.get("curve", [0.0, 0.0]) for seed in seeds])],
        [Reference(1.0, "one"), Reference(0.5, "half", vertical=True)])])]


def toy(run_seed=_square_seed) -> Reproduction:
    return Reproduction("toy-run", "a toy", run_seed, _summary, _rows, _plots)


def test_seeds_in_parallel_processes_give_the_same_results_in_seed_order(tmp_path):
    alone = run(toy(), seeds=3, scale=0.5, jobs=1, out=tmp_path / "one", command="c")
    parallel = run(toy(), seeds=3, scale=0.5, jobs=2, out=tmp_path / "two", command="c")
    assert parallel.seeds == alone.seeds == [
        {"seed": s, "value": s * s * 0.5, "curve": [s, s + 1.0]} for s in range(3)]
    assert parallel.summary == {"total": 2.5}
    assert ((tmp_path / "one" / "toy-run.json").read_text()
            == (tmp_path / "two" / "toy-run.json").read_text())


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_failing_seed_is_reported_by_number_and_nothing_is_written(tmp_path, jobs):
    with pytest.raises(ReproductionFailed, match="toy-run: seed 1 failed: ArithmeticError: no"):
        run(toy(_failing_seed), seeds=3, scale=1.0, jobs=jobs, out=tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_a_result_that_is_not_plain_json_is_refused(tmp_path):
    with pytest.raises(ReproductionFailed, match="not plain JSON"):
        run(toy(_not_json_seed), seeds=1, scale=1.0, jobs=1, out=tmp_path)


def test_replot_redraws_from_the_saved_seeds_without_running_them(tmp_path):
    run(toy(), seeds=2, scale=1.0, jobs=1, out=tmp_path, command="the first run")
    before = (tmp_path / "toy-run.json").read_text()
    (tmp_path / "toy-run.md").unlink()
    outcome = replot(toy(_failing_seed), tmp_path)  # would fail on seed 1 if it ran
    assert outcome.summary == {"total": 1.0}
    assert (tmp_path / "toy-run.json").read_text() == before
    assert "the first run" in (tmp_path / "toy-run.md").read_text()
    (tmp_path / "toy-run.json").write_text('{"seeds": "nothing"')
    with pytest.raises(ReproductionFailed, match="cannot replot"):
        replot(toy(), tmp_path)


def test_the_markdown_table_puts_each_value_beside_its_reference_with_the_gap():
    page = markdown(toy(), [Comparison("steps", 2.25, 0.5, 2.0, "Wilson 1995"),
                            Comparison("problems", 4200.0, 300.0, 5000.0, "Wilson"),
                            Comparison("size", 81.0), Comparison("missing", None, None, 1.0)],
                    ["toy-run-curve.png"], 10, 1.0, "goalagent reproduce toy-run")
    assert "| steps | 2.25 ± 0.5 | 2 | +0.25 (+12%) | Wilson 1995 |" in page
    assert "| problems | 4,200 ± 300 | 5,000 | -800 (-16%) | Wilson |" in page
    assert "| size | 81 | — | — | — |" in page
    assert "| missing | — | 1 | — | — |" in page
    assert "![toy-run-curve.png](toy-run-curve.png)" in page


# -- the command line --------------------------------------------------------------------------

def goalagent(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "goalagent", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


def test_reproduce_list_names_each_reproduction_with_one_line():
    result = goalagent("reproduce", "--list")
    assert result.returncode == 0, result.stderr
    lines = result.stderr.strip().splitlines()
    assert any(line.startswith("xcs-mux ") for line in lines)
    assert any(line.startswith("xcs-woods2 ") for line in lines)
    assert any(line.startswith("appA-params ") for line in lines)


@pytest.mark.parametrize(("args", "message"), [
    (["reproduce", "no-such-thing"], "no reproduction called 'no-such-thing'"),
    (["reproduce"], "name a reproduction"),
    (["reproduce", "xcs-mux", "--seeds", "0"], "--seeds must be at least 1"),
    (["reproduce", "xcs-mux", "--jobs", "0"], "--jobs must be at least 1"),
    (["reproduce", "xcs-mux", "--scale", "1.5"], "--scale must be in (0, 1]"),
])
def test_reproduce_refuses_bad_requests_with_exit_code_2(args, message):
    result = goalagent(*args)
    assert result.returncode == 2
    assert message in result.stderr and "Traceback" not in result.stderr


def test_reproduce_runs_from_the_command_line(tmp_path):
    result = goalagent("reproduce", "xcs-mux", "--seeds", "2", "--jobs", "2", "--scale", "0.02",
                       "--out", str(tmp_path))
    assert result.returncode == 0, result.stderr
    summary = json.loads((tmp_path / "xcs-mux.json").read_text())["summary"]
    assert 0.5 < summary["mux6"]["final_accuracy"] <= 1.0
    assert "6-multiplexer" in result.stderr and "wrote" in result.stderr
