"""Attacks through files (issue 24, item 7): can files, the known-object database and what
they print (the command-line items of item 9 are in test_attacks_cli.py). Each case is the
smallest input that showed a hole: a hang, a traceback ("internal error"), memory without
bound, or raw terminal escapes. Whatever could hang runs in a child process with a timeout."""

from __future__ import annotations

import json
import os
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
from robot.extension import EXTENSION
from sim.canfile import MAX_CAN_BYTES, CanFileError, load_can
from tests.measured import goalagent_measured_each

APP = create_app([EXTENSION])
GOOD_CAN = ("name: x\nmechanism: {type: push_lid}\n"
            "dimensions: {width: 0.22, depth: 0.30, height: 0.26}\n"
            "lid: {height: 0.13, marker_z: 0.11}\n")


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
    for result in goalagent_measured_each(  # in one child: a regression cannot grow this one
            ["snapshot", "--can", str(bomb), "--out", str(tmp_path / "f.png")],
            ["run", "agents/garbage_disposal.mas2g", "--env-param", f"can={bomb}"], timeout=60):
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


@pytest.mark.parametrize("text, where, says", [
    (GOOD_CAN + "\x00", "5:1", "the character U+0000 is not allowed"),
    (GOOD_CAN.replace("name: x", 'name: "\x1b[31mx"'), "1:8", "the character U+001B"),
    (GOOD_CAN.replace("name: x", "name: " + "a" * 60_000), "1:7",
     "name: '" + "a" * 199 + "... (60042 characters)"),
])
def test_control_characters_and_long_values_are_located_and_cut(tmp_path: Path, text: str,
                                                               where: str, says: str):
    path = tmp_path / "can.yaml"
    path.write_text(text)
    with pytest.raises(CanFileError) as raised:
        load_can(path)
    assert str(raised.value).startswith(f"{path}:{where}: "), raised.value
    assert says in str(raised.value) and len(str(raised.value)) < 400


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


@pytest.mark.parametrize("old, new, says", [
    # what JSON reads but no float holds: the schema passes it, the loader does not
    ('"theta": [0.0,', '"theta": [1e400,', "theta of ('lid', 'extend_arm') must hold finite"),
    ('"theta": [0.0,', '"theta": [1' + "0" * 400 + ",", "theta of ('lid', 'extend_arm')"),
    ('"g": [0.0, 1.2]', '"g": [0.0, 1e400]', "g of ('lid', 'extend_arm') must hold finite"),
    ('"lid": [0.002,', '"lid": [1e400,', "the descriptor of part 'lid' must be"),
    ('"functional": null', '"functional": {"part": "lid", "action": "extend_arm", "theta": '
     "1e400}", "the functional theta must be"),
    ('"displacement": [0.0, 0.06, 0.12]', '"displacement": [0.0, 0.06]',
     "has not one theta, displacement and effect per sample"),
    ('"models": [{"part": "lid"', '"models": [{"part": "ghost"', "model for unknown part"),
    # what the schema refuses, at its path
    ('"n_actions": 3', '"n_actions": 1e400', "objects[1].n_actions: must be integer, got inf"),
    ('"n_actions": 3', '"n_actions": true', "objects[1].n_actions: must be integer, got True"),
    ('"effect": [0.0,', '"effect": ["0.0",', "objects[1].models[0].effect[0]: must be number"),
    ('"g": [0.0, 1.2]', '"g": [1.0]', "objects[1].models[0].g: must contain at least 2"),
    ('"name": "o1"', '"name": ["o", 1]', "objects[1].name: must be string"),
])
def test_a_bad_record_is_a_database_error_naming_it(tmp_path: Path, old: str, new: str,
                                                     says: str):
    bad = json.dumps(_record(functional=None))
    assert old in bad
    path = tmp_path / "objects.json"
    path.write_text('{"format": "goalagent-known-objects", "version": 1, "objects": ['
                    + json.dumps(_record("first")) + ", " + bad.replace(old, new, 1) + "]}")
    with pytest.raises(DatabaseError) as raised:
        KnownObjectDatabase(path)
    message = str(raised.value)
    assert says in message and message.startswith("known-object database"), message
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


def test_a_database_that_cannot_be_rewritten_is_a_user_error(tmp_path: Path):
    real = _database(tmp_path / "real.json", _record("o1"))
    link = tmp_path / "objects.json"
    link.symlink_to(real)
    before = real.read_text()
    result = CliRunner().invoke(APP, ["objects", "forget", "o1", "--db", str(link)])
    assert result.exit_code == 2
    assert result.stderr.startswith(f"error: cannot rewrite {link}: {link} is a symbolic link")
    assert real.read_text() == before


def test_file_names_with_terminal_escapes_are_printed_escaped(tmp_path: Path):
    (tmp_path / "a\x1b[2J.goal").write_text("main module { program { if true then print(x). } }\n")
    result = CliRunner().invoke(APP, ["check", str(tmp_path)])
    assert result.exit_code == 0, result.output
    assert result.stderr == f"{tmp_path}/a\\x1b[2J.goal: ok\n"


def test_printable_keeps_lines_and_tabs_and_escapes_what_acts_on_a_terminal():
    assert printable("a\tb\nc") == "a\tb\nc"
    assert printable("\x1b[2J\x9b\x00\u2066x") == "\\x1b[2J\\x9b\\x00\\u2066x"
    assert printable("é ü 中") == "é ü 中"
