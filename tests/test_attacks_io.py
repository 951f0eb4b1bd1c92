"""Attacks through files (issue 24, items 7 and 9): can files, the known-object database and
what they print. Each case is the smallest input that showed a hole: a hang, a traceback
("internal error"), memory without bound, or raw terminal escapes. Whatever could hang runs
in a child process with a timeout."""

from __future__ import annotations

import json
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

from behaviours.learners.known_objects import (
    DatabaseError,
    KnownObjectDatabase,
    StoredModels,
)
from behaviours.learners.part_models import PartActionModel
from behaviours.learners.persist import MAX_STORE_BYTES
from goalagent.cli import create_app
from goalagent.console import printable
from goalagent.parser.source import MAX_PROGRAM_BYTES
from robot.extension import EXTENSION
from sim.canfile import MAX_CAN_BYTES, CanFileError, load_can

ROOT = Path(__file__).resolve().parents[1]
APP = create_app([EXTENSION])
GOOD_CAN = ("name: x\nmechanism: {type: push_lid}\n"
            "dimensions: {width: 0.22, depth: 0.30, height: 0.26}\n"
            "lid: {height: 0.13, marker_z: 0.11}\n")


def goalagent(*args: str, timeout: float = 120) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "goalagent", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=timeout,
                          stdin=subprocess.DEVNULL)


def _laughs(levels: int = 9) -> str:
    """The billion laughs: each level a list of nine aliases of the one before."""
    lines = ['a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]']
    for level in range(1, levels):
        name, before = chr(ord("a") + level), chr(ord("a") + level - 1)
        lines.append(f"{name}: &{name} [" + ", ".join([f"*{before}"] * 9) + "]")
    return "\n".join(lines) + "\n" + GOOD_CAN


# -- can files ---------------------------------------------------------------------------------

def test_a_yaml_bomb_is_refused_by_snapshot_and_by_the_environment(tmp_path: Path):
    bomb = tmp_path / "bomb.yaml"
    bomb.write_text(_laughs())
    for args in (("snapshot", "--can", str(bomb), "--out", str(tmp_path / "f.png")),
                 ("run", "agents/garbage_disposal.mas2g", "--env-param", f"can={bomb}")):
        result = goalagent(*args, timeout=60)
        assert result.returncode == 2, result.stderr
        assert f"{bomb}:2:8: an alias (*a): YAML aliases are not accepted" in result.stderr
        assert "Traceback" not in result.stderr
    assert not (tmp_path / "f.png").exists()


@pytest.mark.parametrize("text, where, says", [
    (GOOD_CAN + "description: &d text\nextra: *d\n", "6:8", "an alias (*d)"),
    ("base: &b {width: 0.2}\ndimensions:\n  <<: *b\n", "3:7", "an alias (*b)"),
    ("name: " + "[" * 30_000 + "]" * 30_000 + "\n", "1:22", "nested more than 16 deep"),
    ("a:\n" + "".join("  " * i + "b:\n" for i in range(1, 40)), "16:31", "nested more than 16"),
    (GOOD_CAN.replace("0.22", "1" * 5000), "3:21", "a number of 5000 characters"),
    (GOOD_CAN.replace("0.22", "1.0e+400"), "3:21", "1.0e+400 is not a finite number"),
    (GOOD_CAN.replace("0.30", ".inf"), "3:34", ".inf is not a finite number"),
    (GOOD_CAN.replace("0.26", ".nan"), "3:48", ".nan is not a finite number"),
])
def test_hostile_yaml_is_a_located_error(tmp_path: Path, text: str, where: str, says: str):
    path = tmp_path / "can.yaml"
    path.write_text(text)
    with pytest.raises(CanFileError) as raised:
        load_can(path)
    assert str(raised.value).startswith(f"{path}:{where}: {says}"), raised.value


def test_only_a_regular_file_of_bounded_size_is_read(tmp_path: Path):
    fifo = tmp_path / "fifo.yaml"
    os.mkfifo(fifo)  # nobody writes: a blocking read would wait for ever
    big = tmp_path / "big.yaml"
    big.write_text(GOOD_CAN + "#" * MAX_CAN_BYTES)
    latin = tmp_path / "latin.yaml"
    latin.write_bytes(GOOD_CAN.encode() + b"description: caf\xe9\n")
    for path, says in ((fifo, ":1:1: cannot read the can file: a FIFO, not a regular file"),
                       (Path("/dev/zero"), ":1:1: cannot read the can file: a device, not a "
                                           "regular file"),
                       (tmp_path, ":1:1: cannot read the can file: a directory, not a "
                                  "regular file"),
                       (big, f":1:1: cannot read the can file: {big.stat().st_size} bytes: "
                             f"larger than the {MAX_CAN_BYTES} bytes accepted"),
                       (latin, ":5:17: not UTF-8 text (byte 0xe9)")):
        with pytest.raises(CanFileError) as raised:
            load_can(path)
        assert str(raised.value) == f"{path}{says}"


def test_snapshot_of_a_hostile_can_is_one_error_line_with_exit_2(tmp_path: Path):
    path = tmp_path / "deep.yaml"
    path.write_text("name: " + "[" * 100 + "]" * 100 + "\n")
    result = CliRunner().invoke(APP, ["snapshot", "--can", str(path), "--out",
                                      str(tmp_path / "f.png")])
    assert result.exit_code == 2
    assert result.stderr == f"error: {path}:1:22: nested more than 16 deep\n"


# -- the known-object database -----------------------------------------------------------------

def _record(name: str = "o1", **changes: object) -> dict:
    record = {"name": name, "parts": {"lid": [0.002, 0.4, 1.0], "body": [0.005, 0.46, 1.0]},
              "above": [["lid", "body"]], "bounds": {"extend_arm": [0.0, 0.1]},
              "models": [{"part": "lid", "action": "extend_arm", "theta": [0.0, 0.05, 0.1],
                          "displacement": [0.0, 0.06, 0.12], "effect": [0.0, 0.05, 0.11],
                          "g": [0.0, 1.2], "h": [0.0, 0.9]}],
              "functional": {"part": "lid", "action": "extend_arm", "theta": 0.06},
              "n_actions": 3, "source": None, "extra": {"can_file": "o1.yaml"}}
    record.update(changes)
    return record


def _database(path: Path, *records: dict) -> Path:
    path.write_text(json.dumps({"format": "goalagent-known-objects", "version": 1,
                                "objects": list(records)}))
    return path


def _model(**changes: object) -> list[dict]:
    return [{**_record()["models"][0], **changes}]


@pytest.mark.parametrize("record, says", [
    (_record(n_actions=1e400), "n_actions must be a whole number"),
    (_record(n_actions=-1), "n_actions must be a whole number"),
    (_record(n_actions=True), "n_actions must be a whole number"),
    (_record(models=_model(theta=[1e400, 0.0, 0.1])), "theta of ('lid', 'extend_arm')"),
    (_record(models=_model(theta=[10 ** 400, 0, 1])), "theta of ('lid', 'extend_arm')"),
    (_record(models=_model(effect=[0.0, "0.1", 0.2])), "effect of ('lid', 'extend_arm')"),
    (_record(models=_model(effect=[0.0, True, 0.2])), "effect of ('lid', 'extend_arm')"),
    (_record(models=_model(displacement=[0.0, 0.1])), "not one theta, displacement and effect"),
    (_record(models=_model(g=[1.0])), "needs g and h as [intercept, slope]"),
    (_record(parts={"lid": [1e400, 0.4, 1.0]}), "the descriptor of part 'lid'"),
    (_record(name=["o", 1]), "the name must be a string"),
    (_record(name="x" * 201), "the name must be a string of 1 to 200 characters"),
    (_record(functional={"part": "lid", "action": "extend_arm", "theta": 1e400}),
     "the functional theta"),
    (_record(extra=[1, 2]), "extra must be a mapping"),
])
def test_a_bad_record_is_a_database_error_naming_it(tmp_path: Path, record: dict, says: str):
    path = _database(tmp_path / "objects.json", _record("first"), record)
    with pytest.raises(DatabaseError) as raised:
        KnownObjectDatabase(path)
    message = str(raised.value)
    assert "has a bad record (object 1)" in message and says in message, message
    assert len(message) < 400  # the values are quoted shortened


@pytest.mark.parametrize("text, says", [
    ('{"objects": [' + "1" * 5000 + "]}", "Exceeds the limit (4300 digits)"),
    ("[" * 100_000 + "]" * 100_000, "JSON nested too deeply"),
])
def test_numbers_and_nesting_past_json_s_means_are_errors_not_crashes(tmp_path: Path,
                                                                    text: str, says: str):
    path = tmp_path / "objects.json"
    path.write_text(text)
    result = CliRunner().invoke(APP, ["objects", "list", "--db", str(path)])
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith("error: cannot read known-object database") and (
        says in result.stderr), result.stderr


def test_a_database_past_the_stated_size_is_refused_before_it_is_read(tmp_path: Path):
    path = tmp_path / "objects.json"
    with path.open("wb") as stream:
        stream.truncate(MAX_STORE_BYTES + 1)  # sparse: no disk used
    with pytest.raises(DatabaseError, match=f"{MAX_STORE_BYTES + 1} bytes, more than the "
                                            f"{MAX_STORE_BYTES} accepted"):
        KnownObjectDatabase(path)


def test_models_are_checked_on_load_and_fitted_when_first_asked_for(tmp_path: Path):
    path = _database(tmp_path / "objects.json", _record("o1"), _record("o2"))
    database = KnownObjectDatabase(path)
    models = database.get("o1").models
    assert isinstance(models, StoredModels) and len(models) == 1
    assert models._fitted == {}  # loading fitted nothing
    model = models["lid", "extend_arm"]
    expected = PartActionModel().fit([0.0, 0.05, 0.1], [0.0, 0.06, 0.12], [0.0, 0.05, 0.11])
    assert (model.g_intercept_, model.g_slope_) == pytest.approx((0.0, 1.2))
    assert (model.h_intercept_, model.h_slope_) == pytest.approx(
        (expected.h_intercept_, expected.h_slope_))
    assert models["lid", "extend_arm"] is model  # fitted once
    entry = json.loads(path.read_text())["objects"][1]["models"][0]
    database.forget("o1")  # rewrites the file: o2's unread model goes back as it was read
    assert json.loads(path.read_text())["objects"][0]["models"][0] == entry


def test_names_with_terminal_escapes_or_markup_are_printed_escaped(tmp_path: Path):
    red, bidi = "\x1b[31m", "\u202e"
    record = _record(f"o{red}x", parts={f"lid{bidi}": [0.002, 0.4, 1.0]}, above=[],
                     models=[], functional=None, extra={"can_file": "[bold]can[/bold]\x07"})
    path = _database(tmp_path / "objects.json", record)
    listed = CliRunner().invoke(APP, ["objects", "list", "--db", str(path)])
    shown = CliRunner().invoke(APP, ["objects", "show", f"o{red}x", "--db", str(path)])
    missing = CliRunner().invoke(APP, ["objects", "show", "none", "--db", str(path)])
    assert listed.exit_code == 0 and shown.exit_code == 0 and missing.exit_code == 2
    for output in (listed.stdout, shown.stdout, missing.stderr):
        assert "\x1b" not in output and bidi not in output and "\x07" not in output
        assert "o\\x1b[31mx" in output
    assert "[bold]can[/bold]\\x07" in listed.stdout and "lid\\u202e" in listed.stdout


def test_printable_keeps_lines_and_tabs_and_escapes_what_acts_on_a_terminal():
    assert printable("a\tb\nc") == "a\tb\nc"
    assert printable("\x1b[2J\x9b\x00\u2066x") == "\\x1b[2J\\x9b\\x00\\u2066x"
    assert printable("é ü 中") == "é ü 中"


# -- the smaller items (issue 24, item 9) ------------------------------------------------------

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
    assert len(result.stderr) < 300


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
