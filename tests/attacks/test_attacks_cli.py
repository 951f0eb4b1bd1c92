"""Attacks through the command line (issue 24, item 9): program files too large to parse, an
agent file that is no GOAL file, impossible options, output paths that are links or devices
or cannot be written, and signals at start-up, while running and with nobody reading. What
could hang runs in a child process with a timeout."""

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

from goalagent.cli import create_app
from goalagent.parser.source import MAX_PROGRAM_BYTES
from robot.extension import EXTENSION

ROOT = Path(__file__).resolve().parents[2]
APP = create_app([EXTENSION])

WALKER = """
init module { beliefs { at(0). } program { if true then print(started). } }
main module { program {
    if bel(at(N), M is N + 1) then delete(at(N)) + insert(at(M)) + insert(visited(M)).
} }
"""


def test_a_2_mb_one_line_program_is_refused_before_it_is_parsed(tmp_path: Path):
    path = tmp_path / "long.goal"
    path.write_text("init module { beliefs { " + "p(1). " * 350_000 + "} }")
    result = CliRunner().invoke(APP, ["check", str(path)])
    assert result.exit_code == 2
    assert result.stderr == (f"{path}:1:1: cannot read file: {path.stat().st_size} bytes: larger "
                             f"than the {MAX_PROGRAM_BYTES} bytes accepted\n")


def test_an_unexpected_token_is_quoted_shortened(tmp_path: Path):
    path = tmp_path / "token.goal"
    path.write_text("a" * 100_000)
    result = CliRunner().invoke(APP, ["check", str(path)])
    assert result.exit_code == 2
    assert result.stderr.startswith(f"{path}:1:1: unexpected '{'a' * 40}'... (100000 "
                                    "characters), expected")
    assert all(len(line) < 300 for line in result.stderr.splitlines())


def test_an_agent_file_that_is_no_goal_file_is_refused_without_quoting_it(tmp_path: Path):
    secret = tmp_path / "secret"
    secret.write_text("SECRET-TOKEN:x:0:0\n")
    system = tmp_path / "a" / "b" / "s.mas2g"
    system.parent.mkdir(parents=True)
    system.write_text('agentfiles { "..\\\\..\\\\secret". }\n')
    for command in ("check", "run"):
        result = CliRunner().invoke(APP, [command, str(system)])
        assert result.exit_code == 2, result.output
        assert "not a GOAL agent file (its name ends in .goal)" in result.stderr
        assert "SECRET" not in result.output


@pytest.mark.parametrize("port, says", [("70000", "less than or equal to 65535"),
                                        ("-1", "greater than or equal to 0")])
def test_an_impossible_port_is_a_usage_error(tmp_path: Path, port: str, says: str):
    program = tmp_path / "w.goal"
    program.write_text(WALKER)
    result = CliRunner().invoke(APP, ["run", str(program), "--inspect", "--port", port])
    assert result.exit_code == 2
    assert "Invalid value for '--port'" in result.output and says in result.output
    assert "Traceback" not in result.output


def _link_to(tmp_path: Path, name: str) -> tuple[Path, Path]:
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    link = tmp_path / name
    link.symlink_to(victim)
    return link, victim


@pytest.mark.parametrize("option", ["--save-beliefs", "--trace-file"])
def test_a_save_or_trace_path_that_is_a_link_is_refused(tmp_path: Path, option: str):
    program = tmp_path / "w.goal"
    program.write_text(WALKER)
    link, victim = _link_to(tmp_path, "out.pl")
    result = CliRunner().invoke(APP, ["run", str(program), "--max-cycles", "2", option,
                                      str(link), "--save-predicate", "visited/1"])
    assert result.exit_code == 2, result.output
    assert f"{link} is a symbolic link (to {victim})" in result.stderr
    assert victim.read_text() == "precious\n" and link.is_symlink()


def test_a_trace_file_on_a_device_is_refused_and_the_device_left_alone(tmp_path: Path):
    if os.geteuid() != 0:
        pytest.skip("making a device node needs root")
    device = tmp_path / "full"
    os.mknod(device, 0o666 | stat.S_IFCHR, os.makedev(1, 7))  # what /dev/full is
    program = tmp_path / "w.goal"
    program.write_text(WALKER)
    result = CliRunner().invoke(APP, ["run", str(program), "--max-cycles", "2",
                                      "--trace-file", str(device)])
    assert result.exit_code == 2
    assert result.stderr == (f"error: --trace-file {device}: {device} exists and is not a "
                             "regular file\n")
    assert stat.S_ISCHR(device.lstat().st_mode)


def test_a_trace_that_cannot_be_written_is_an_error_and_the_old_trace_stays(tmp_path: Path):
    program = tmp_path / "w.goal"
    program.write_text(WALKER)
    trace = tmp_path / "trace.txt"
    trace.write_text("the last trace\n")
    script = ("import resource, signal, sys\n"
              "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
              "resource.setrlimit(resource.RLIMIT_FSIZE, (20_000, 20_000))\n"
              "sys.argv = ['goalagent', *sys.argv[1:]]\n"
              "from goalagent.launcher import main\n"
              "main()\n")
    result = subprocess.run([sys.executable, "-c", script, "run", str(program), "--max-cycles",
                             "400", "--trace-file", str(trace)], capture_output=True,
                            text=True, timeout=300, cwd=ROOT)
    assert result.returncode == 1, result.stderr
    assert (f"error: --trace-file: cannot write the trace file {trace}: File too large"
            in result.stderr)
    assert "w: stopped at the cycle limit after 400 cycles" in result.stderr
    assert trace.read_text() == "the last trace\n"
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []


def _caught_signals(pid: int) -> int:
    with open(f"/proc/{pid}/status") as status:
        return int(next(line.split()[1] for line in status if line.startswith("SigCgt:")), 16)


@pytest.mark.parametrize("closed", [False, True])
def test_sighup_saves_and_exits_129_even_with_nobody_reading(tmp_path: Path, closed: bool):
    program = tmp_path / "w.goal"
    program.write_text(WALKER)
    saved = tmp_path / "saved.pl"
    child = subprocess.Popen([sys.executable, "-m", "goalagent", "run", str(program),
                              "--save-beliefs", str(saved), "--save-predicate", "visited/1",
                              "--save-every", "1"], cwd=ROOT, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, env={**os.environ, "PYTHONUNBUFFERED": "1"})
    assert child.stdout is not None and child.stderr is not None
    assert child.stdout.readline() == b"started\n"
    deadline = time.monotonic() + 120
    while not (saved.exists() and saved.read_text().count("visited(") >= 10):
        assert time.monotonic() < deadline
        time.sleep(0.05)
    if closed:  # the terminal is gone: every write fails
        child.stdout.close()
        child.stderr.close()
    child.send_signal(signal.SIGHUP)
    assert child.wait(timeout=60) == 129
    if not closed:
        stderr = child.stderr.read().decode()
        assert "interrupted (SIGHUP)" in stderr and f"to {saved}" in stderr, stderr
        child.stderr.close()
        child.stdout.close()
    facts = re.findall(r"^visited\((\d+)\)\.$", saved.read_text(), re.M)
    assert [int(n) for n in facts] == list(range(1, len(facts) + 1)) and len(facts) >= 10


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT, signal.SIGHUP])
def test_a_signal_while_starting_is_said_and_gives_its_exit_code(tmp_path: Path, signum: int):
    program = tmp_path / "w.goal"
    program.write_text(WALKER)
    child = subprocess.Popen([sys.executable, "-m", "goalagent", "run", str(program),
                              "--max-cycles", "3"], cwd=ROOT, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while not _caught_signals(child.pid) & (1 << (signal.SIGHUP - 1)):  # installed last
        assert time.monotonic() < deadline and child.poll() is None
        time.sleep(0.002)
    child.send_signal(signum)
    stdout, stderr = child.communicate(timeout=60)
    assert child.returncode == 128 + signum, stderr
    assert stderr == f"goalagent: stopped by {signal.Signals(signum).name}\n"  # importing
    assert stdout == ""
