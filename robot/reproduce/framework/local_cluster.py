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
POLL_SECONDS = 0.1
"""How often a starting cluster is asked whether it is up."""
STOP_SECONDS = 10.0
"""How long stopping the nodes may take: every process of theirs is killed (SIGKILL, by process
id) until none is left. A raylet given SIGTERM took about ten seconds to shut down, and the
head's GCS and ``ray start`` lingered on after it; killed at once they leave nothing behind in
/dev/shm, and the cluster's folder is removed."""
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
            if index == 0:
                _wait_for_head(port, nodes[0])
        _wait_for_nodes(address, len(cpus), nodes)
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


def _wait_for_head(port: int, head: subprocess.Popen) -> None:
    """Until the head's GCS takes connections on ``port``: the other nodes start then, side by
    side with the rest of the head's start (a node retries the GCS for about 20 s, Ray's
    NUM_REDIS_GET_RETRIES, but not for as long as a head can take to start on a busy
    machine). RuntimeError when the head ended or START_SECONDS passed."""
    deadline = time.monotonic() + START_SECONDS
    while True:
        if head.poll() is not None:
            raise RuntimeError("the head's ray start process ended before its GCS listened")
        if time.monotonic() > deadline:
            raise RuntimeError(f"the head's GCS did not listen within {START_SECONDS:.0f} s")
        with contextlib.suppress(OSError), socket.create_connection(("127.0.0.1", port), 1):
            return
        time.sleep(POLL_SECONDS)


def _wait_for_nodes(address: str, count: int, nodes: list[subprocess.Popen]) -> None:
    """Until ``count`` nodes are alive in the cluster, asked of one connection to it
    (RuntimeError when a node's process ended or START_SECONDS passed)."""
    import ray

    deadline = time.monotonic() + START_SECONDS

    def check() -> None:
        if any(node.poll() is not None for node in nodes):
            raise RuntimeError("a ray start process ended before its node joined")
        if time.monotonic() > deadline:
            raise RuntimeError(f"the cluster did not have {count} nodes within "
                               f"{START_SECONDS:.0f} s")

    while True:
        check()
        try:
            ray.init(address=address, logging_level="ERROR", log_to_driver=False)
            break
        except ConnectionError:
            time.sleep(POLL_SECONDS)
    try:
        while sum(node["Alive"] for node in ray.nodes()) < count:
            check()
            time.sleep(POLL_SECONDS)
    finally:
        ray.shutdown()


def _stop(cluster: LocalCluster) -> None:
    """SIGKILL every process of the nodes by process id, again while any is left, for at most
    STOP_SECONDS."""
    deadline = time.monotonic() + STOP_SECONDS
    while (left := cluster.processes()) and time.monotonic() < deadline:
        for pid, *_ in left:
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
        time.sleep(POLL_SECONDS)
