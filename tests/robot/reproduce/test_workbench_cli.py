"""``goalagent reproduce`` and ``goalagent sweep`` as a user reaches them: the issue's commands,
bad input as one line and exit 2, shards merged, pages redrawn, and a run that is interrupted
(Ctrl-C) or killed (SIGKILL) resuming from its cache."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.conftest import cli

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

ROOT = Path(__file__).resolve().parents[3]


@pytest.fixture(scope="module")
def cache(tmp_path_factory) -> Path:
    """One cache for the module: later commands reuse the seeds earlier ones finished."""
    return tmp_path_factory.mktemp("cache")


def test_reproduce_records_a_set_value_in_the_config(tmp_path, cache):
    # --jobs 1: this process (the sweep below takes the command's --jobs 2 path)
    result = cli("reproduce", "xcs-mux", "--quick", "--set", "N=400", "--jobs", "1",
                 "--out", str(tmp_path), "--cache", str(cache))
    assert result.exit_code == 0, result.stderr
    document = json.loads((tmp_path / "xcs-mux.json").read_text())
    assert document["config"]["N"] == 400 and document["config"]["scale"] == 0.05
    assert document["command"] == ("goalagent reproduce xcs-mux --seeds 2 --set scale=0.05 "
                                   "--set N=400")
    assert "claim: XCS solves the 6-multiplexer" in result.stderr
    assert "seeds run: 2, from the cache: 0" in result.stderr


def test_sweep_writes_one_cell_per_value_each_with_cis(tmp_path, cache):
    """Two seeds a cell: N = 400's come from the cache, N = 200's run in the command's pool of
    two worker processes (--jobs 2), one seed each; a third seed a cell made each worker run
    two seeds instead of one (0.5 s CPU) and checked nothing more."""
    result = cli("sweep", "xcs-mux", "--quick", "--grid", "N=200,400", "--seeds", "2",
                 "--jobs", "2", "--out", str(tmp_path), "--cache", str(cache))
    assert result.exit_code == 0, result.stderr
    assert "seeds run: 2, from the cache: 2" in result.stderr  # N = 400, seeds 0-1: cached
    document = json.loads((tmp_path / "xcs-mux-sweep-N.json").read_text())
    assert [cell["values"] for cell in document["cells"]] == [{"N": 200}, {"N": 400}]
    for cell in document["cells"]:
        assert [record["seed"] for record in cell["seeds"]] == [0, 1]
        accuracy = cell["summary"]["metrics"][0]
        assert accuracy["key"] == "mux6.final_accuracy" and accuracy["n"] == 2
        assert accuracy["ci"][0] <= accuracy["mean"] <= accuracy["ci"][1]
    page = (tmp_path / "xcs-mux-sweep-N.md").read_text()
    assert "| N | 6-multiplexer: fraction correct, last 50 exploit problems |" in page
    for key in ("mux6-final_accuracy", "mux6-problems_to_99", "mux11-final_accuracy"):
        assert f"](xcs-mux-sweep-N-{key}.png)" in page
    before = page
    assert cli("sweep", "xcs-mux", "--replot", "--out", str(tmp_path)).exit_code == 0
    assert (tmp_path / "xcs-mux-sweep-N.md").read_text() == before


def test_shards_run_elsewhere_merge_and_replot(tmp_path, cache):
    for offset in ("0", "1"):
        result = cli("reproduce", "xcs-mux", "--quick", "--set", "N=400", "--seeds", "1",
                     "--seed-offset", offset, "--jobs", "1", "--out",
                     str(tmp_path / offset), "--cache", str(cache))
        assert result.exit_code == 0 and "from the cache: 1" in result.stderr
    result = cli("reproduce", "merge", str(tmp_path / "0" / "xcs-mux.json"),
                 str(tmp_path / "1" / "xcs-mux.json"), "--out", str(tmp_path / "all"))
    assert result.exit_code == 0, result.stderr
    merged = json.loads((tmp_path / "all" / "xcs-mux.json").read_text())
    assert [record["seed"] for record in merged["seeds"]] == [0, 1]
    assert merged["command"] == ("goalagent reproduce xcs-mux --seeds 2 --set scale=0.05 "
                                 "--set N=400")
    page = (tmp_path / "all" / "xcs-mux.md").read_text()
    (tmp_path / "all" / "xcs-mux.md").unlink()
    assert cli("reproduce", "xcs-mux", "--replot", "--out",
               str(tmp_path / "all")).exit_code == 0
    assert (tmp_path / "all" / "xcs-mux.md").read_text() == page


def test_list_and_params_describe_the_studies():
    listed = cli("reproduce", "--list").stderr.splitlines()
    assert any(line.startswith("xcs-mux ") and "multiplexer" in line for line in listed)
    modules = [path for path in (ROOT / "robot" / "reproduce" / "studies").glob("*.py")
               if path.name != "__init__.py"]
    assert len(listed) == len(modules)  # one line per study module, each named as its file
    assert sorted(line.split()[0].replace("-", "_") for line in listed) == sorted(
        path.stem for path in modules)
    params = cli("reproduce", "ch4-exploration", "--params").stderr
    assert "tolerance" in params and "0.0001" in params and "(eq. 4.10)" in params


@pytest.mark.parametrize(("args", "message"), [
    (["reproduce", "xcs-mx"], "no study called 'xcs-mx' (did you mean 'xcs-mux'"),
    (["reproduce"], "name a study"),
    (["reproduce", "xcs-mux", "--seeds", "0"], "--seeds must be at least 1"),
    (["reproduce", "xcs-mux", "--seed-offset", "-1"], "--seed-offset must be at least 0"),
    (["reproduce", "xcs-mux", "--jobs", "0"], "--jobs must be at least 1"),
    (["reproduce", "xcs-mux", "--out", "a-file"], "--out a-file exists and is not a folder"),
    (["reproduce", "xcs-mux", "--scale", "1.5"], "scale: Input should be less than or equal"),
    (["reproduce", "xcs-mux", "--set", "Nn=4"], "has no parameter 'Nn'; did you mean 'N'?"),
    (["reproduce", "xcs-mux", "--set", "N=many"], "N=many: N: Input should be a valid integer"),
    (["reproduce", "ch5-baseline", "--scale", "0.5"], "ch5-baseline has no parameter 'scale'"),
    (["reproduce", "ch5-baseline", "--set", "cans=[\"o9\"]"], "o9"),
    (["reproduce", "xcs-mux", "--ray", "nowhere"], "give 'auto' or HOST:PORT"),
    (["reproduce", "xcs-mux", "--ray", "127.0.0.1:1"], "no Ray cluster answers there"),
    (["reproduce", "xcs-mux", "--ray", "auto", "--jobs", "2"], "--jobs is for local processes"),
    (["reproduce", "xcs-mux", "extra.json"], "unexpected arguments after xcs-mux"),
    (["reproduce", "merge", "a.json"], "needs two or more shards"),
    (["reproduce", "merge", "no.json", "nor.json"], "no.json: cannot read it"),
    (["reproduce", "xcs-mux", "--replot", "--out", "nowhere"], "nowhere/xcs-mux.json: cannot"),
    (["sweep", "xcs-mux", "--quick"], "a sweep needs at least one --grid"),
    (["sweep", "xcs-mux", "--grid", "N="], "none may be empty"),
    (["sweep", "xcs-mux", "--grid", "M=1,2"], "xcs-mux has no parameter 'M'"),
    (["sweep", "xcs-mux", "--grid", "N=1"], "N: Input should be greater than or equal to 2"),
    (["sweep", "xcs-mux", "--replot", "--out", "nowhere"], "no xcs-mux-sweep-*.json in"),
])
def test_bad_input_is_one_line_and_exit_2(args, message, tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))  # nothing may land in ~/.cache
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a-file").write_text("")
    result = cli(*args)
    assert result.exit_code == 2, result.stderr
    assert message in result.stderr and result.stderr.count("error:") == 1


def _entries(cache: Path) -> int:
    return len(list((cache / "xcs-mux").glob("*.json"))) if (cache / "xcs-mux").exists() else 0


def _until_cached(process: subprocess.Popen, cache: Path, count: int) -> None:
    deadline = time.monotonic() + 300
    while _entries(cache) < count:
        assert process.poll() is None, process.stderr.read() if process.stderr else ""
        assert time.monotonic() < deadline
        time.sleep(0.1)


def test_an_interrupted_or_killed_run_resumes_from_its_cache(tmp_path):
    """Ctrl-C (SIGINT) and SIGKILL each stop a run after some seeds finished; the next run of
    the same command runs only the seeds that had not. The two runs that are stopped are
    processes of their own, for the signals; the last, which only has to finish, runs in this
    process (cli()), which spares a third start-up of the command (the test 6.3 -> 4.3 s CPU)."""
    cache = tmp_path / "cache"
    arguments = ["reproduce", "xcs-mux", "--quick", "--seeds", "4", "--jobs", "1", "--out",
                 str(tmp_path / "out"), "--cache", str(cache)]
    command = [sys.executable, "-m", "goalagent", *arguments]
    environment = {**os.environ, "MUJOCO_GL": "egl"}
    first = subprocess.Popen(command, cwd=ROOT, stderr=subprocess.PIPE, text=True,
                             env=environment)
    _until_cached(first, cache, 1)
    first.send_signal(signal.SIGINT)
    assert first.wait(timeout=120) == 130
    assert "interrupted: every seed that finished is cached" in first.stderr.read()
    done = _entries(cache)
    second = subprocess.Popen(command, cwd=ROOT, stderr=subprocess.PIPE, text=True,
                              env=environment)
    _until_cached(second, cache, done + 1)
    second.kill()
    second.wait(timeout=60)
    done = _entries(cache)
    assert done >= 2
    third = cli(*arguments)
    assert third.exit_code == 0, third.stderr
    assert f"seeds run: {4 - done}, from the cache: {done}" in third.stderr
    document = json.loads((tmp_path / "out" / "xcs-mux.json").read_text())
    assert [record["seed"] for record in document["seeds"]] == [0, 1, 2, 3]
