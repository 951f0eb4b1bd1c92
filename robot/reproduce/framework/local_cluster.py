"""A Ray cluster on this machine, for trying ``--ray`` without a cluster, for the tests and the
benchmark: a head and more node processes, each ``ray start --block`` in a session of its own,
with token authentication on (a token made for this cluster) and stopped by process id.

Ray itself decides where its servers listen (the head's GCS on every interface, the nodes on
the machine's address even when told 127.0.0.1); the token is what keeps others out.
"""

from __future__ import annotations

import contextlib
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

START_SECONDS = 180.0
STOP_SECONDS = 2.0
"""How long the nodes get to stop after SIGTERM before what is left is killed by process id
(the raylets take about ten seconds to shut down, and the head's GCS and ``ray start`` linger
on after them; killed at once they leave nothing behind in /dev/shm, and the cluster's
folder is removed)."""
OBJECT_STORE_BYTES = 80_000_000
TASK_TITLE = "ray::run_on_worker"
"""The process title of a Ray worker while it runs one of the workbench's tasks."""


@dataclass(frozen=True)
class LocalCluster:
    """A running cluster: its address, its token and the nodes' process groups."""

    address: str
    environment: dict[str, str]
    """os.environ with the cluster's token: give it to every driver (``goalagent ... --ray``)."""
    groups: tuple[int, ...]

    def processes(self) -> list[tuple[int, int, int, str, str]]:
        """The living processes of the nodes, (pid, group, parent, state, command line): the
        ``ray start`` groups and the workers their raylets started (each leads a group)."""
        rows = [row for row in _processes() if not row[3].startswith("Z")]
        members = {row[0] for row in rows if row[1] in self.groups}
        return [row for row in rows if row[0] in members or row[2] in members]

    def task_workers(self) -> list[int]:
        """The worker processes running one of the workbench's tasks now."""
        return [pid for pid, _, _, _, args in self.processes() if args.startswith(TASK_TITLE)]


def _processes() -> list[tuple[int, int, int, str, str]]:
    listing = subprocess.run(["ps", "-eo", "pid=,pgid=,ppid=,stat=,args="], capture_output=True,
                             text=True, check=True).stdout
    rows = []
    for line in listing.splitlines():
        pid, group, parent, state, *args = line.split(None, 4)
        rows.append((int(pid), int(group), int(parent), state, args[0] if args else ""))
    return rows


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _ray_command() -> str:
    return str(Path(sys.executable).with_name("ray"))


@contextlib.contextmanager
def local_cluster(cpus: tuple[int, ...] = (1, 1)) -> Iterator[LocalCluster]:
    """A head with ``cpus[0]`` CPUs and one more node per further entry; the token is set in
    this process's environment while the cluster runs (this process can drive it)."""
    folder = Path(tempfile.mkdtemp(prefix="rwb", dir="/tmp"))  # short: Ray's socket paths
    port = _free_port()
    address = f"127.0.0.1:{port}"
    token = {"RAY_AUTH_MODE": "token", "RAY_AUTH_TOKEN": secrets.token_hex(16)}
    environment = {**os.environ, **token, "MUJOCO_GL": os.environ.get("MUJOCO_GL", "egl")}
    saved = {key: os.environ.get(key) for key in token}
    os.environ.update(token)
    nodes: list[subprocess.Popen] = []
    try:
        for index, count in enumerate(cpus):
            where = (["--head", f"--port={port}", "--node-ip-address=127.0.0.1",
                      "--include-dashboard=false", f"--temp-dir={folder}"] if index == 0
                     else [f"--address={address}"])
            log = (folder / f"node{index}.log").open("w")
            nodes.append(subprocess.Popen(
                [_ray_command(), "start", "--block", f"--num-cpus={count}",
                 "--disable-usage-stats", f"--object-store-memory={OBJECT_STORE_BYTES}", *where],
                env=environment, stdout=log, stderr=subprocess.STDOUT, start_new_session=True))
            _wait_for_nodes(address, index + 1, nodes)
        yield LocalCluster(address, environment, tuple(node.pid for node in nodes))
    finally:
        cluster = LocalCluster(address, environment, tuple(node.pid for node in nodes))
        _stop(cluster)
        for node in nodes:
            node.wait(timeout=30)
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value
        shutil.rmtree(folder, ignore_errors=True)


def _wait_for_nodes(address: str, count: int, nodes: list[subprocess.Popen]) -> None:
    """Until ``count`` nodes are alive in the cluster (RuntimeError when one ended)."""
    import ray

    deadline = time.monotonic() + START_SECONDS
    while True:
        if any(node.poll() is not None for node in nodes):
            raise RuntimeError("a ray start process ended before its node joined")
        if time.monotonic() > deadline:
            raise RuntimeError(f"the cluster did not have {count} nodes within "
                               f"{START_SECONDS:.0f} s")
        try:
            ray.init(address=address, logging_level="ERROR", log_to_driver=False)
        except ConnectionError:
            time.sleep(1)
            continue
        try:
            if sum(node["Alive"] for node in ray.nodes()) >= count:
                return
        finally:
            ray.shutdown()
        time.sleep(0.5)


def _stop(cluster: LocalCluster) -> None:
    """SIGTERM each node's group; after STOP_SECONDS, SIGKILL what is left, by process id."""
    for group in cluster.groups:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(group, signal.SIGTERM)
    deadline = time.monotonic() + STOP_SECONDS
    while time.monotonic() < deadline and cluster.processes():
        time.sleep(0.5)
    for pid, *_ in cluster.processes():
        with contextlib.suppress(ProcessLookupError):
            os.kill(pid, signal.SIGKILL)
