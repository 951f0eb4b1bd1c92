"""Shared pytest set-up, and the two ways the tests run the ``goalagent`` command.

MuJoCo renders headless (EGL) unless the caller chose a backend, and OpenMP runs one thread.
:func:`goalagent` runs the command in a child process, as a user does: for what needs a process
of its own (its exit status and streams as the shell sees them, signals, the interpreter's
start-up, anything that would change the test process). :func:`cli` runs it in this process
through click's ``CliRunner``, built as the console script builds it: for argument validation,
exit codes, help and messages, without a Python start-up.
:func:`python` runs a snippet in a child Python.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

if TYPE_CHECKING:
    from collections.abc import Iterator

    import click
    import typer
    from click.testing import Result

os.environ.setdefault("MUJOCO_GL", "egl")
# One OpenMP (and OpenBLAS) thread in the test processes and their children: the suite runs two
# workers on two cores, and scikit-learn's parallel loops (a nearest-neighbour search over five
# parts, say) spun their threads against the other worker, taking 0.1 s a call instead of a
# millisecond. Set before anything loads numpy (nothing has when pytest reads this file); a
# value the caller set is kept.
os.environ.setdefault("OMP_NUM_THREADS", "1")

ROOT = Path(__file__).resolve().parents[1]
"""The repository's root: the child processes' default working directory."""


@pytest.hookimpl(wrapper=True)
def pytest_collection() -> Iterator[object]:
    """Collection may write bytecode, whatever PYTHONDONTWRITEBYTECODE says: pytest keeps the
    test modules it rewrote for their asserts only where Python may write bytecode, and with
    the variable set (this machine, many CI images) each worker rewrote all of them again
    on every run, about 4 of its 7.5 s of collection. Only during collection: what the
    tests import or run afterwards writes no bytecode, as the variable asks."""
    writes = sys.dont_write_bytecode
    sys.dont_write_bytecode = False
    try:
        return (yield)
    finally:
        sys.dont_write_bytecode = writes


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The modules marked ``heavy`` (5 s or more on an idle machine: a cluster, reproductions,
    processes) first, the rest in their order: ``make test`` hands whole files to its two
    workers in this order, and a heavy file handed out last leaves the other worker idle
    (test_saving.py's 13 s, handed out near the end, ended one worker 9 s after the other)."""
    items.sort(key=lambda item: item.get_closest_marker("heavy") is None)


def _child(command: list[str], cwd: Path, timeout: float, env: dict[str, str] | None,
           input: str | None) -> subprocess.CompletedProcess[str]:
    """``command`` to its end (a child still running after ``timeout`` seconds, a hang, fails
    the calling test through ``subprocess.TimeoutExpired``); stdin is ``input``, or empty so
    that no child waits on the terminal; ``env`` adds to this process's environment."""
    return subprocess.run(command, cwd=cwd, capture_output=True, text=True, timeout=timeout,
                          env={**os.environ, **(env or {})}, input=input,
                          stdin=None if input is not None else subprocess.DEVNULL)


def goalagent(*args: str, cwd: Path = ROOT, timeout: float = 300,
              env: dict[str, str] | None = None,
              input: str | None = None) -> subprocess.CompletedProcess[str]:
    """``python -m goalagent ARGS`` in a child process."""
    return _child([sys.executable, "-m", "goalagent", *args], cwd, timeout, env, input)


def python(code: str, *args: str, cwd: Path = ROOT, timeout: float = 120,
           env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    """``python -c CODE ARGS`` in a child process (``code`` is dedented)."""
    return _child([sys.executable, "-c", textwrap.dedent(code), *args], cwd, timeout, env,
                  None)


@cache
def _installed_command() -> click.Command:
    """The ``goalagent`` command as its console script runs it (the installed extensions,
    readable metavars), made once per session."""
    from goalagent.cli import command

    return command()


def cli(*args: str, app: typer.Typer | None = None, input: str | None = None,
        env: dict[str, str] | None = None) -> Result:
    """``goalagent ARGS`` in this process (the installed command, or ``app``'s), ``input`` on
    its stdin, ``env`` added to the environment while it runs; an exception escaping the
    command fails the calling test, as a traceback would."""
    import typer.main
    from click.testing import CliRunner

    command = typer.main.get_command(app) if app is not None else _installed_command()
    result = CliRunner().invoke(command, list(args), input=input, env=env,
                                prog_name="goalagent", catch_exceptions=False)
    assert "Traceback" not in result.stderr, result.stderr
    return result
