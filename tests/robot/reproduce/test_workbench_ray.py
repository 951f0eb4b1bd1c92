"""The Ray backend against a real cluster started here with ``ray start``: a head node and a
second node process on this machine, one CPU each, token authentication on with a token made
for this run (``robot/reproduce/framework/local_cluster.py``). A run on the cluster gives the
local run's document but for the seconds; a sweep goes on, losing no seed, when a worker
process is killed with SIGKILL mid-task. The module stops the cluster it started."""

from __future__ import annotations

import json
import os
import signal
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from typer.testing import CliRunner

from goalagent.cli import create_app
from robot.reproduce.framework.local_cluster import LocalCluster, local_cluster

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

APP = create_app()


@pytest.fixture(scope="module")
def cluster() -> Iterator[LocalCluster]:
    with local_cluster((1, 1)) as running:
        yield running


def _document(folder: Path, name: str) -> dict:
    document = json.loads((folder / f"{name}.json").read_text())
    for record in [r for cell in document.get("cells", [document]) for r in cell["seeds"]]:
        record.pop("seconds")
    return document


@pytest.fixture(scope="module")
def local(tmp_path_factory) -> dict:
    """xcs-mux at its quick size with N = 400, seeds 0-2, run here (--jobs 1: this process;
    local processes give the same document, test_workbench.py's
    test_parallel_processes_give_the_same_document_but_for_the_seconds, and two spawned
    workers would only add their start-up)."""
    out = tmp_path_factory.mktemp("local")
    result = CliRunner().invoke(APP, ["reproduce", "xcs-mux", "--quick", "--set", "N=400",
                                      "--seeds", "3", "--jobs", "1", "--out", str(out),
                                      "--fresh", "--cache", str(out / "cache")])
    assert result.exit_code == 0, result.stderr
    return _document(out, "xcs-mux")


def test_a_run_on_the_cluster_gives_the_local_document_but_for_the_seconds(cluster, local,
                                                                           tmp_path):
    result = CliRunner().invoke(APP, ["reproduce", "xcs-mux", "--quick", "--set", "N=400",
                                      "--seeds", "3", "--ray", cluster.address, "--out",
                                      str(tmp_path), "--cache", str(tmp_path / "cache")])
    assert result.exit_code == 0, result.stderr
    assert "seeds run: 3, from the cache: 0" in result.stderr
    assert _document(tmp_path, "xcs-mux") == local
    assert local["summary"]["metrics"][0]["ci"] is not None


def test_a_sweep_survives_a_worker_killed_mid_task(cluster, local, tmp_path):
    """The sweep runs in this process (its driver needs no process of its own: the run above
    drives the cluster from here too); a thread beside it kills the first worker it sees
    running a task. A child process for the sweep only added a start-up (Ray, scikit-learn
    and SciPy imported again: 3 s CPU)."""
    killed: list[int] = []
    failures: list[BaseException] = []
    finished = threading.Event()

    def kill_a_worker() -> None:
        try:
            deadline = time.monotonic() + 240
            while not (workers := cluster.task_workers()):
                if finished.is_set():
                    return
                assert time.monotonic() < deadline, "no worker ever ran a task"
                time.sleep(0.1)
            os.kill(workers[0], signal.SIGKILL)
            killed.append(workers[0])
        except BaseException as error:  # noqa: BLE001 - reported by the test below
            failures.append(error)

    killer = threading.Thread(target=kill_a_worker, daemon=True)
    killer.start()
    try:
        result = CliRunner().invoke(APP, ["sweep", "xcs-mux", "--quick", "--grid", "N=200,400",
                                          "--seeds", "3", "--ray", cluster.address, "--out",
                                          str(tmp_path), "--cache", str(tmp_path / "cache")],
                                    env=cluster.environment)
    finally:
        finished.set()
        killer.join(timeout=60)
    assert not failures, failures
    assert killed, "the sweep ended before a worker could be killed"
    assert result.exit_code == 0, result.stderr
    assert "seeds run: 6, from the cache: 0" in result.stderr
    document = _document(tmp_path, "xcs-mux-sweep-N")
    assert [[r["seed"] for r in cell["seeds"]] for cell in document["cells"]] == [[0, 1, 2]] * 2
    at_400 = document["cells"][1]
    assert at_400["values"] == {"N": 400}
    assert at_400["seeds"] == local["seeds"] and at_400["summary"] == local["summary"]
