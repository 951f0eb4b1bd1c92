"""The Ray backend against a real cluster started here with ``ray start``: a head node and a
second node process on this machine, one CPU each, token authentication on with a token made
for this run. A run on the cluster gives the local run's document but for the seconds; a
sweep goes on, losing no seed, when a worker process is killed with SIGKILL mid-task. The
module stops the cluster it started (both nodes' process groups, nothing else)."""

from __future__ import annotations

import contextlib
import json
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest
from typer.testing import CliRunner

from goalagent.cli import create_app

ROOT = Path(__file__).resolve().parents[1]
RAY = Path(sys.executable).with_name("ray")
APP = create_app()
STOP_SECONDS = 12
"""How long the nodes get to stop after SIGTERM before the rest is killed."""
TASK_TITLE = "ray::run_on_worker"
"""The process title of a Ray worker while it runs a task of ours."""


@dataclass(frozen=True)
class Cluster:
    address: str
    groups: tuple[int, ...]
    """The process groups of the two ``ray start --block`` processes (each its own session)."""
    environment: dict[str, str]


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _start(arguments: list[str], environment: dict[str, str], log: Path) -> subprocess.Popen:
    return subprocess.Popen([str(RAY), "start", "--block", "--num-cpus=1",
                             "--disable-usage-stats", *arguments],
                            env=environment, stdout=log.open("w"), stderr=subprocess.STDOUT,
                            start_new_session=True)


def _wait_for_nodes(address: str, count: int, nodes: list[subprocess.Popen]) -> None:
    import ray

    deadline = time.monotonic() + 180
    while True:
        for node in nodes:
            assert node.poll() is None, "a ray start process ended"
        try:
            ray.init(address=address, logging_level="ERROR", log_to_driver=False)
        except ConnectionError:
            assert time.monotonic() < deadline, "the head never answered"
            time.sleep(1)
            continue
        try:
            while sum(node["Alive"] for node in ray.nodes()) < count:
                assert time.monotonic() < deadline, "the second node never joined"
                time.sleep(0.5)
            return
        finally:
            ray.shutdown()


def _processes() -> list[tuple[int, int, int, str, str]]:
    """(pid, process group, parent, state, command line) of every process."""
    listing = subprocess.run(["ps", "-eo", "pid=,pgid=,ppid=,stat=,args="], capture_output=True,
                             text=True, check=True).stdout
    rows = []
    for line in listing.splitlines():
        pid, group, parent, state, *args = line.split(None, 4)
        rows.append((int(pid), int(group), int(parent), state, args[0] if args else ""))
    return rows


def _ours(groups: tuple[int, ...]) -> list[tuple[int, int, int, str, str]]:
    """The living processes of the two nodes: their groups, and the Ray workers their raylets
    started (each worker leads a group of its own)."""
    rows = [row for row in _processes() if not row[3].startswith("Z")]
    members = {row[0] for row in rows if row[1] in groups}
    return [row for row in rows if row[0] in members or row[2] in members]


def _stop(groups: tuple[int, ...]) -> None:
    """SIGTERM each group we started (ray start --block stops its raylet and workers within
    seconds, but the head's GCS and the ``ray start`` process itself linger on for good); then
    SIGKILL whatever of the nodes is still alive, by process id."""
    for group in groups:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(group, signal.SIGTERM)
    deadline = time.monotonic() + STOP_SECONDS
    while time.monotonic() < deadline and _ours(groups):
        time.sleep(0.5)
    for pid, *_ in _ours(groups):
        with contextlib.suppress(ProcessLookupError):
            os.kill(pid, signal.SIGKILL)


@pytest.fixture(scope="module")
def cluster() -> Iterator[Cluster]:
    folder = Path(tempfile.mkdtemp(prefix="rwb", dir="/tmp"))  # short: Ray's socket paths
    port = _free_port()
    address = f"127.0.0.1:{port}"
    token = {"RAY_AUTH_MODE": "token", "RAY_AUTH_TOKEN": secrets.token_hex(16)}
    environment = {**os.environ, **token, "MUJOCO_GL": "egl"}
    head = _start(["--head", f"--port={port}", "--node-ip-address=127.0.0.1",
                   "--include-dashboard=false", f"--temp-dir={folder}",
                   "--object-store-memory=80000000"], environment, folder / "head.log")
    nodes = [head]
    saved = {key: os.environ.get(key) for key in token}
    os.environ.update(token)
    try:
        _wait_for_nodes(address, 1, nodes)
        nodes.append(_start([f"--address={address}", "--object-store-memory=80000000"],
                            environment, folder / "node.log"))
        _wait_for_nodes(address, 2, nodes)
        yield Cluster(address, tuple(node.pid for node in nodes), environment)
    finally:
        _stop(tuple(node.pid for node in nodes))
        for node in nodes:
            node.wait(timeout=30)
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value
        shutil.rmtree(folder, ignore_errors=True)


def _document(folder: Path, name: str) -> dict:
    document = json.loads((folder / f"{name}.json").read_text())
    for record in [r for cell in document.get("cells", [document]) for r in cell["seeds"]]:
        record.pop("seconds")
    return document


@pytest.fixture(scope="module")
def local(tmp_path_factory) -> dict:
    """xcs-mux at its quick size with N = 400, seeds 0-2, on local processes."""
    out = tmp_path_factory.mktemp("local")
    result = CliRunner().invoke(APP, ["reproduce", "xcs-mux", "--quick", "--set", "N=400",
                                      "--seeds", "3", "--jobs", "2", "--out", str(out),
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


def _our_task_workers(groups: tuple[int, ...]) -> list[int]:
    """Ray worker processes of this cluster running one of our tasks now."""
    return [pid for pid, _, _, _, args in _ours(groups) if args.startswith(TASK_TITLE)]


def test_a_sweep_survives_a_worker_killed_mid_task(cluster, local, tmp_path):
    command = [sys.executable, "-m", "goalagent", "sweep", "xcs-mux", "--quick", "--grid",
               "N=200,400", "--seeds", "3", "--ray", cluster.address, "--out", str(tmp_path),
               "--cache", str(tmp_path / "cache")]
    sweep = subprocess.Popen(command, cwd=ROOT, env=cluster.environment,
                             stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 240
        while not (workers := _our_task_workers(cluster.groups)):
            assert sweep.poll() is None, sweep.stderr.read()
            assert time.monotonic() < deadline, "no worker ever ran a task"
            time.sleep(0.1)
        os.kill(workers[0], signal.SIGKILL)
        assert sweep.wait(timeout=600) == 0, sweep.stderr.read()
    finally:
        if sweep.poll() is None:
            sweep.kill()
            sweep.wait()
    assert "seeds run: 6, from the cache: 0" in sweep.stderr.read()
    document = _document(tmp_path, "xcs-mux-sweep-N")
    assert [[r["seed"] for r in cell["seeds"]] for cell in document["cells"]] == [[0, 1, 2]] * 2
    at_400 = document["cells"][1]
    assert at_400["values"] == {"N": 400}
    assert at_400["seeds"] == local["seeds"] and at_400["summary"] == local["summary"]
