"""Cans as data: the shipped can files, and a located error for every kind of broken file."""

from __future__ import annotations

from pathlib import Path

import pytest

from sim.canfile import CanFileError, find_can, load_can, parse_can, shipped_cans
from sim.scene import CANS, asset_path, build_mjcf

GOOD = """\
name: mine
mechanism:
  type: lift_handle
  gear: 9.0
dimensions:
  width: 0.22
  depth: 0.30
  height: 0.26
lid:
  height: 0.03
  marker_z: 0.015
handle:
  drop: 0.12
"""


def test_the_thesis_cans_come_from_their_files_and_make_todays_scenes():
    assert set(CANS) == {"o1", "o2", "o3", "o4", "o5"}
    assert {"o1", "o2", "o3", "o4", "o5", "slide", "pedal"} <= set(shipped_cans())
    for name, spec in CANS.items():
        assert spec.source.endswith(f"{name}.yaml")
        assert build_mjcf(spec) == asset_path(name).read_text()  # the committed scenes
    assert CANS["o5"].functional == ("handle", "contract_arm")
    assert find_can("slide").functional == ("lid", "sweep_left")
    assert find_can("pedal").parts == ("body", "lid", "pedal")


def test_a_can_file_anywhere_is_found_by_its_path(tmp_path: Path):
    path = tmp_path / "mine.yaml"
    path.write_text(GOOD)
    spec = find_can(str(path))
    assert (spec.name, spec.gear, spec.handle_drop, spec.functional) == (
        "mine", 9.0, 0.12, ("handle", "lift_up"))
    assert load_can(path) == spec
    with pytest.raises(CanFileError, match="unknown can 'o9': name a shipped can"):
        find_can("o9")
    with pytest.raises(CanFileError, match="missing.yaml:1:1: cannot read the can file"):
        find_can(str(tmp_path / "missing.yaml"))


@pytest.mark.parametrize(("change", "where", "message"), [
    (("  gear: 9.0\n", "  gear: 9.0\n  twist: 1\n"), "5:3", "unknown key 'twist'; allowed here"),
    (("  width: 0.22", "  width: wide"), "6:10", "dimensions.width: 'wide' is not of type"),
    (("  width: 0.22", "  width: 0.9"), "6:10", "0.9 is greater than the maximum of 0.3"),
    (("type: lift_handle", "type: twist_lid"), "3:9", "'twist_lid' is not one of"),
    (("  gear: 9.0\n", ""), "3:3", "a lift_handle mechanism needs a gear"),
    (("  marker_z: 0.015", "  marker_z: 0.05"), "11:13", "puts the 2 cm marker off"),
    (("  drop: 0.12", "  drop: 0.2"), "13:9", "puts the handle over the body marker"),
    (("name: mine", "name: Mine Can"), "1:7", "does not match"),
    (("lid:\n  height: 0.03\n  marker_z: 0.015\n", ""), "1:1", "'lid' is missing"),
    (("  drop: 0.12\n", "  drop: 0.12\ncolours:\n  body: [0.9, 0.1, 0.1]\n"), "15:9",
     "too dark or too colourful"),
    (("  height: 0.26\n", "  height: 0.26\n  height: 0.27\n"), "9:3", "'height' appears twice"),
    (("  gear: 9.0", "  gear: [9.0"), "5:11", "not valid YAML"),
])
def test_broken_can_files_are_located_errors(tmp_path: Path, change, where, message):
    path = tmp_path / "broken.yaml"
    path.write_text(GOOD.replace(*change))
    with pytest.raises(CanFileError) as caught:
        find_can(str(path))
    assert str(caught.value).startswith(f"{path}:{where}: "), str(caught.value)
    assert message in str(caught.value)


def test_mechanism_specific_rules():
    slide = GOOD.replace("type: lift_handle", "type: slide_lid").replace("handle:\n  drop: 0.12\n",
                                                                          "")
    with pytest.raises(CanFileError, match="needs a direction"):
        parse_can(slide, "s.yaml")
    slide = slide.replace("  gear: 9.0", "  gear: 1.2\n  direction: right")
    with pytest.raises(CanFileError, match=r"s.yaml:12:3: a sliding lid carries its marker"):
        parse_can(slide, "s.yaml")
    spec = parse_can(slide.replace("  marker_z: 0.015\n", ""), "s.yaml")
    assert spec.functional == ("lid", "sweep_right")
    with pytest.raises(CanFileError, match=r"p.yaml:11:1: a push_lid can has no handle"):
        parse_can(GOOD.replace("type: lift_handle", "type: push_lid").replace(
            "  gear: 9.0\n", ""), "p.yaml")
    with pytest.raises(CanFileError, match="<can>:1:1: a can file is a mapping"):
        parse_can("- o1\n")


def test_the_garbage_environment_takes_a_can_file(tmp_path: Path):
    from goalagent.eis import ManagementException, load_environment

    path = tmp_path / "mine.yaml"
    path.write_text(GOOD)
    env = load_environment("garbage")()
    env.init({"can": str(path), "models": str(tmp_path / "models.json")})
    env.start()
    env.register_agent("robot")
    env.associate_entity("robot", "robot")
    seen = {str(p) for p in env.get_all_percepts("robot")["robot"]}
    assert {"obs(body)", "obs(lid)", "obs(handle)"} <= seen
    env.kill()
    path.write_text(GOOD.replace("  gear: 9.0\n", ""))
    with pytest.raises(ManagementException, match=rf"{path}:3:3: a lift_handle mechanism needs"):
        load_environment("garbage")().init({"can": str(path)})
