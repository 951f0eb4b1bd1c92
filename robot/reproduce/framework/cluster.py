"""The Ray backend (``--ray ADDRESS``): each (config, seed) a Ray task on an existing cluster,
run again when its worker or node is lost, its result handed back to this process, which
caches it at once. Ray is the ``cluster`` extra (``pip install goalagent[cluster]``).

A worker finds the study by name in this package and rebuilds the config from its JSON, so
the cluster's nodes need goalagent installed (the same version: the provenance of each seed
records the node's), nothing else.
"""

from __future__ import annotations

import contextlib
import logging
import os
import re
import socket
import sys
import tempfile
from collections.abc import Iterator, Sequence

from robot.reproduce.framework.backends import RETRIES, Done, Report
from robot.reproduce.framework.provenance import Provenance
from robot.reproduce.framework.tasks import Finished, ReproductionFailed, Task, execute

ADDRESS = re.compile(r"(?P<host>[A-Za-z0-9.\-]+|\[[0-9A-Fa-f:]+\]):(?P<port>[0-9]{1,5})")
CONNECT_SECONDS = 5.0
"""How long a HOST:PORT may take to accept a connection before it counts as unreachable."""
WAIT_SECONDS = 0.5


class ClusterError(ValueError):
    """Ray is missing or the cluster cannot be reached (a user's error: exit 2)."""


def check_address(address: str) -> None:
    """``auto`` or a reachable ``HOST:PORT``; ClusterError in one line otherwise."""
    if address == "auto":
        return
    match = ADDRESS.fullmatch(address)
    if match is None or not 0 < int(match["port"]) < 65536:
        raise ClusterError(f"--ray {address!r}: give 'auto' or HOST:PORT of the cluster's head")
    host = match["host"].strip("[]")
    try:
        with socket.create_connection((host, int(match["port"])), timeout=CONNECT_SECONDS):
            pass
    except OSError as error:
        raise ClusterError(f"--ray {address}: no Ray cluster answers there "
                           f"({error.strerror or error})") from None


def _import_ray():
    try:
        import ray
    except ImportError:
        raise ClusterError("--ray needs Ray: pip install 'goalagent[cluster]' (or run "
                           "scripts/setup.sh)") from None
    return ray


@contextlib.contextmanager
def _quiet_stderr() -> Iterator[None]:
    """File descriptor 2 into a scratch file while Ray joins a cluster: its C++ client logs
    each failed attempt (a wrong token, a cluster going down) before its own logging is set
    up; the user gets one line from us instead."""
    sys.stderr.flush()
    saved = os.dup(2)
    try:
        with tempfile.TemporaryFile() as scratch:
            os.dup2(scratch.fileno(), 2)
            try:
                yield
            finally:
                os.dup2(saved, 2)
    finally:
        os.close(saved)


class RayBackend:
    """Tasks on the Ray cluster at ``address`` (``auto``: the one started on this machine)."""

    def __init__(self, address: str) -> None:
        check_address(address)
        self.address = address
        self.ray = _import_ray()

    def connect(self) -> None:
        """Join the cluster (ClusterError when it cannot be joined); ``run`` leaves it."""
        if self.ray.is_initialized():
            return
        try:
            with _quiet_stderr():
                self.ray.init(address=self.address, logging_level=logging.ERROR,
                              log_to_driver=False)
        except (ConnectionError, RuntimeError, ValueError) as error:
            raise ClusterError(f"--ray {self.address}: cannot join the cluster: "
                               f"{str(error).splitlines()[0]}") from None

    def run(self, tasks: Sequence[Task], report: Report, finished: Done) -> None:
        ray = self.ray
        self.connect()
        try:
            remote = ray.remote(num_cpus=1, max_retries=RETRIES, retry_exceptions=False)(
                run_on_worker)
            refs = {remote.remote(task.study.name, task.config.model_dump(mode="json"),
                                  task.seed): index for index, task in enumerate(tasks)}
            waiting = list(refs)
            try:
                while waiting:
                    done, waiting = ray.wait(waiting, num_returns=1, timeout=WAIT_SECONDS)
                    for ref in done:
                        index = refs[ref]
                        finished(index, self._collect(ref, tasks[index]))
                        report(index, 1.0)
            except BaseException:
                for ref in waiting:
                    ray.cancel(ref, force=True)
                raise
        finally:
            ray.shutdown()

    def _collect(self, ref: object, task: Task) -> Finished:
        """The task's finished result from its Ray object; a failure names the seed."""
        ray = self.ray
        try:
            payload = ray.get(ref)
        except ray.exceptions.RayTaskError as error:
            cause = getattr(error, "cause", None)
            if isinstance(cause, ReproductionFailed):
                raise ReproductionFailed(str(cause)) from None
            raise ReproductionFailed(f"{task.study.name}: seed {task.seed} failed on the "
                                     f"cluster: {cause or error}") from None
        except ray.exceptions.RayError as error:
            raise ReproductionFailed(f"{task.study.name}: seed {task.seed} was lost "
                                     f"{RETRIES + 1} times on the cluster: "
                                     f"{type(error).__name__}") from None
        return Finished(task, task.study.result.model_validate(payload["result"]),
                        payload["seconds"], Provenance.model_validate(payload["provenance"]))


def run_on_worker(study_name: str, config: dict, seed: int) -> dict:
    """One task on a Ray worker: the study by name, the config from its JSON. (MUJOCO_GL is
    set here rather than in a runtime environment, which would keep Ray from using the
    workers it started in advance.)"""
    from robot.reproduce.framework.registry import find

    os.environ.setdefault("MUJOCO_GL", "egl")
    study = find(study_name)
    done = execute(Task(study, study.config.model_validate(config), seed), lambda f: None)
    return {"result": done.result.model_dump(mode="json"), "seconds": done.seconds,
            "provenance": done.provenance.model_dump(mode="json")}
