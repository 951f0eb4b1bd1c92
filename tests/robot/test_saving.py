"""Learned knowledge is saved as it is learned: atomically (kill -9 at any moment leaves the
last complete save), every --save-every, before any report, and when Ctrl-C or SIGTERM stop
the run (issue 14 item 4, issue 19 items 2 and 4)."""

from __future__ import annotations

import os
import re
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

import ondisk
from goalagent.beliefs import SaveInterval, read_belief_file, write_atomically
from goalagent.cli import create_app
from goalagent.extensions import Extension, RunContext, RunHook
from robot.affordance import AFFORD

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

ROOT = Path(__file__).resolve().parents[2]

# Says it started, then learns one visited/1 fact per cycle, for ever.
WALKER = """
init module { beliefs { at(0). } program { if true then print(started). } }
main module { program {
    if bel(at(N), M is N + 1) then delete(at(N)) + insert(at(M)) + insert(visited(M)).
} }
"""


def _start(*args: str, cwd: Path) -> subprocess.Popen[str]:
    """``goalagent ARGS`` in a child whose first line of output is the walker's ``started``."""
    child = subprocess.Popen([sys.executable, "-m", "goalagent", *args], cwd=cwd,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             env={**os.environ, "PYTHONUNBUFFERED": "1"})
    assert child.stdout is not None and child.stdout.readline() == "started\n"
    return child


def _visited(path: Path) -> list[int]:
    """The visited/1 facts of a saved file, which must load as a whole."""
    with read_belief_file(path, []) as facts:
        assert facts.count >= 0
    found = [int(n) for n in re.findall(r"^visited\((\d+)\)\.$", path.read_text(), re.M)]
    return found


def _first_line(path: Path) -> str:
    with path.open() as stream:
        return stream.readline().rstrip("\n")


def _wait_for(condition, seconds: float = 120) -> None:
    deadline = time.monotonic() + seconds
    while not condition():
        assert time.monotonic() < deadline, "timed out waiting"
        time.sleep(0.05)


@pytest.fixture
def walker(tmp_path: Path) -> Path:
    path = tmp_path / "walker.goal"
    path.write_text(WALKER)
    return path


def test_save_every_parses_cycles_durations_and_end():
    assert SaveInterval.parse("100") == SaveInterval(cycles=100)
    assert SaveInterval.parse("30s") == SaveInterval(seconds=30)
    assert SaveInterval.parse("5m") == SaveInterval(seconds=300)
    assert SaveInterval.parse("end") == SaveInterval()
    for bad in ("", "0", "-3", "x", "3x", "1e99"):
        with pytest.raises(ValueError, match="--save-every"):
            SaveInterval.parse(bad)


@pytest.mark.parametrize("signum, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_stops_the_run_saves_and_exits_with_its_code(walker: Path, tmp_path: Path,
                                                              signum: int, code: int):
    saved = tmp_path / "saved.pl"
    child = _start("run", str(walker), "--save-beliefs", str(saved), "--save-predicate",
                   "visited/1", "--save-every", "1", cwd=tmp_path)
    _wait_for(lambda: saved.exists() and len(_visited(saved)) >= 20)
    child.send_signal(signum)
    _, stderr = child.communicate(timeout=60)
    assert child.returncode == code, stderr
    name = signal.Signals(signum).name
    assert re.search(rf"interrupted \({name}\) (in agent walker, cycle|after agent "
                     rf"walker's cycle) \d+: stopping", stderr)
    assert re.search(r"walker: interrupted after \d+ cycles", stderr)
    assert "saved" in stderr and "Traceback" not in stderr
    visited = _visited(saved)
    assert visited == list(range(1, len(visited) + 1)) and len(visited) >= 20


def test_kill_9_at_any_moment_leaves_the_last_complete_save(walker: Path, tmp_path: Path):
    """What a kill -9 would leave at a moment is what the file holds then (a save replaces it
    whole, or not at all): one run, its file read at moments from its first save to 0.6 s
    later (each a save a kill there would have left: dozens of saves, each a moment of its
    own; later ones only write a longer file), then killed with -9."""
    saved = tmp_path / "saved.pl"
    child = _start("run", str(walker), "--save-beliefs", str(saved), "--save-predicate",
                   "visited/1", "--save-every", "1", cwd=tmp_path)
    _wait_for(lambda: saved.exists())
    first, counts = time.monotonic(), []
    for moment in (0.0, 0.02, 0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.6):
        time.sleep(max(0.0, first + moment - time.monotonic()))
        visited = _visited(saved)  # it loads: whole
        assert visited == list(range(1, len(visited) + 1))  # and complete
        counts.append(len(visited))
    child.kill()
    child.communicate(timeout=60)
    visited = _visited(saved)
    assert visited == list(range(1, len(visited) + 1)) and len(visited) >= counts[-1]
    assert len(set(counts)) >= 2, counts  # the moments saw different saves


def test_writes_killed_midway_never_leave_a_partial_file(tmp_path: Path):
    """A child rewrites a 2 MB file in a loop (each version whole lines of one number) and
    is killed at random moments: the file is always one complete version. The child takes
    the writer the saves use (goalagent.beliefs imports it) from ondisk, its home: importing
    it through goalagent.beliefs cost each child 0.2 s of the parser and the engine."""
    assert write_atomically is ondisk.write_atomically
    target = tmp_path / "beliefs.pl"
    script = (
        "import sys, itertools\n"
        "from pathlib import Path\n"
        "from ondisk import write_atomically\n"
        "for n in itertools.count():\n"
        "    write_atomically(Path(sys.argv[1]), f'v({n}).\\n' * 200_000)\n"
    )
    versions = set()
    # (a version takes milliseconds to write: any delay lands in the loop at a moment of
    # its own, and each second the loop runs costs its CPU)
    for delay in (0.0, 0.03, 0.1, 0.2, 0.35):
        child = subprocess.Popen([sys.executable, "-c", script, str(target)])
        _wait_for(lambda: target.exists() and _first_line(target) not in versions)
        time.sleep(delay)
        child.send_signal(signal.SIGKILL)
        child.wait(timeout=60)
        lines = target.read_text().splitlines()
        assert len(lines) == 200_000 and len(set(lines)) == 1
        versions.add(lines[0])
    leftovers = [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]
    assert len(leftovers) <= 5  # at most one temporary file per kill, never the target
    assert len(versions) >= 2  # the kills did come at different moments


def test_a_second_ctrl_c_ends_the_finishing_save_at_once(walker: Path, tmp_path: Path):
    many = tmp_path / "many.pl"
    many.write_text("".join(f"seen({n}, x{n % 97}).\n" for n in range(100_000)))
    saved = tmp_path / "saved.pl"
    saved.write_text("% the previous save\n")
    child = _start("run", str(walker), "--load-beliefs", str(many), "--save-beliefs",
                   str(saved), "--save-predicate", "seen/2", "--save-every", "end",
                   cwd=tmp_path)
    child.send_signal(signal.SIGINT)
    assert child.stderr is not None
    said = child.stderr.readline()  # the final save of 100,000 facts (a second or two) starts
    assert said.endswith("stopping, finishing the run\n"), said
    stopped = time.monotonic()
    child.send_signal(signal.SIGINT)
    _, stderr = child.communicate(timeout=60)
    assert child.returncode == 130, stderr
    assert time.monotonic() - stopped < 10
    assert "SIGINT: stopped at once; what was being saved or reported is left as it was" in (
        stderr)
    assert saved.read_text() == "% the previous save\n"  # the previous file is whole
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]


class _Broken(RunHook):
    """A report that fails, and that checks the beliefs were saved before it ran."""

    seen_saved: list[bool] = []

    def after_cycle(self, run: RunContext, agent: object) -> None:
        raise RuntimeError("broken after a cycle")

    def finish(self, run: RunContext) -> None:
        _Broken.seen_saved.append(Path(str(run.options["save_beliefs"])).exists())
        raise OSError(28, "No space left on device")


def test_reports_run_after_the_save_and_a_failing_one_costs_nothing_learned(walker: Path,
                                                                           tmp_path: Path):
    app = create_app([Extension(name="broken", run_hooks=(_Broken,))])
    saved = tmp_path / "saved.pl"
    _Broken.seen_saved = []
    result = CliRunner().invoke(app, ["run", str(walker), "--max-cycles", "5", "--save-beliefs",
                                      str(saved), "--save-predicate", "visited/1"])
    assert result.exit_code == 1  # a hook failed: said, and the exit code says it too
    assert _Broken.seen_saved == [True]
    assert result.stderr.count("error: run hook _Broken failed at after_cycle: RuntimeError: "
                               "broken after a cycle") == 1
    assert ("error: run hook _Broken failed at finish: OSError: No space left on device"
            in result.stderr)
    assert _visited(saved) == [1, 2, 3, 4, 5]
    assert "walker: stopped at the cycle limit after 5 cycles" in result.stderr


class _Sabotage(RunHook):
    """Puts a folder where --save-beliefs writes, once the run has started."""

    def start(self, run: RunContext) -> None:
        Path(str(run.options["save_beliefs"])).mkdir()


def test_a_periodic_save_that_fails_is_a_warning_and_the_run_goes_on(walker: Path,
                                                                      tmp_path: Path):
    target = tmp_path / "saved.pl"
    result = CliRunner().invoke(create_app([Extension(name="x", run_hooks=(_Sabotage,))]), [
        "run", str(walker), "--max-cycles", "4", "--save-beliefs", str(target),
        "--save-predicate", "visited/1", "--save-every", "1"])
    assert result.exit_code == 1
    assert result.stderr.count(f"warning: cannot save beliefs to {target}") == 1
    assert (f"error: run hook BeliefSaver failed at finish: TargetError: {target} exists and "
            "is not a regular file") in result.stderr
    assert "walker: stopped at the cycle limit after 4 cycles" in result.stderr


class _Swallower(RunHook):
    """Sends the run SIGINT after its third cycle and swallows the stop, as code that catches
    everything (or Python, for an exception raised in ``__del__``) would."""

    def after_cycle(self, run: RunContext, agent: object) -> None:
        if getattr(agent, "cycle", 0) == 3:
            try:
                os.kill(os.getpid(), signal.SIGINT)
                time.sleep(1)  # the handler runs here, and its stop is swallowed below
            except BaseException:  # noqa: BLE001, S110 - the point of the test
                pass


def test_a_stop_that_something_swallowed_still_ends_the_run_a_cycle_later(walker: Path,
                                                                           tmp_path: Path):
    saved = tmp_path / "saved.pl"
    result = CliRunner().invoke(create_app([Extension(name="x", run_hooks=(_Swallower,))]), [
        "run", str(walker), "--max-cycles", "50", "--save-beliefs", str(saved),
        "--save-predicate", "visited/1"])
    assert result.exit_code == 130, result.stderr
    assert "interrupted (SIGINT)" in result.stderr
    assert _visited(saved) == [1, 2, 3, 4]  # the stop came with the next cycle's end


def test_a_save_never_replaces_what_is_not_a_regular_file(walker: Path, tmp_path: Path):
    fifo = tmp_path / "fifo.pl"
    os.mkfifo(fifo)
    result = CliRunner().invoke(create_app([]), ["run", str(walker), "--max-cycles", "1",
                                                 "--save-beliefs", str(fifo),
                                                 "--save-predicate", "visited/1"])
    assert result.exit_code == 2
    assert result.stderr.strip() == (f"error: --save-beliefs {fifo}: {fifo} exists and is not "
                                     "a regular file")
    assert stat.S_ISFIFO(fifo.lstat().st_mode)
    with pytest.raises(OSError, match="not a regular file"):
        write_atomically(fifo, "x.\n")
    assert stat.S_ISFIFO(fifo.lstat().st_mode)


def test_a_garbage_world_run_killed_with_kill_9_keeps_what_it_learned(tmp_path: Path):
    saved = tmp_path / "exp1.pl"
    child = subprocess.Popen(
        [sys.executable, "-m", "goalagent", "run", str(ROOT / "agents" / "garbage_disposal.mas2g"),
         "--save-beliefs", str(saved), "--save-every", "1", "--plot", str(tmp_path / "p.png"),
         "--env-param", f"models={tmp_path / 'models.json'}"],
        cwd=tmp_path, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    learned = re.compile(r"^afford\(lid,\w+,opened,[1-9]\d*,\d+,[\d.]+\)\.$", re.M)
    try:
        _wait_for(lambda: saved.exists() and bool(learned.search(saved.read_text())), 300)
    finally:
        child.kill()
        child.wait(timeout=60)
    with read_belief_file(saved, [AFFORD]) as facts:  # whole, and afford/6's types hold
        assert facts.count >= 6
    assert learned.search(saved.read_text())
