"""The environment reference is read from the code (goalagent/eis/reference.py): defaults as
the code reads them, actions as the methods take them, the percepts an agent really gets;
the hand-written pages name every percept and action it finds."""

from __future__ import annotations

from pathlib import Path

import pytest

from goalagent.eis import known_environments, load_environment
from goalagent.eis.reference import _grouped, describe, markdown
from goalagent.mas import parse_parameter

ROOT = Path(__file__).resolve().parents[3]
GOAL_ENVIRONMENTS = ROOT / "goalagent" / "eis" / "envs" / "README.md"
PAGES = {"goalagent.eis.envs.bw4t": GOAL_ENVIRONMENTS,
         "goalagent.eis.envs.elevator": GOAL_ENVIRONMENTS,
         "goalagent.eis.envs.hanoi": GOAL_ENVIRONMENTS,
         "robot.envs": ROOT / "robot" / "envs" / "README.md"}
SIMPLE = ("blocksworld", "towerworld", "printer", "hanoi")


def _first_percepts(name: str, params: dict) -> list[str]:
    environment = load_environment(name)()
    try:
        environment.init(params)
        environment.start()
        entity = environment.entities()[0]
        environment.register_agent("reader")
        environment.associate_entity("reader", entity)
        return sorted(str(p) for p in environment.get_all_percepts("reader")[entity])
    finally:
        environment.kill()


def test_hanoi_reads_as_its_code_says() -> None:
    doc = describe("hanoi")
    assert doc.summary == "Discs on three pins, moved one at a time onto larger ones."
    discs = next(p for p in doc.parameters if p.name == "discs")
    assert discs.default == "[0,0,0,0]" and discs.meaning == "pin of each disc, largest first"
    [move] = doc.actions
    assert move.name == "move" and move.parameters == ("disc: an integer", "to: an integer")
    assert doc.entities == (("entity", "hanoicontroller"),)
    assert "disc(1,10)" in doc.percepts
    text = markdown(doc)
    assert "| `discs` | `[0,0,0,0]` | pin of each disc, largest first |" in text
    assert "| `disc/2` | 4 | `disc(4,7)` |" in text


@pytest.mark.parametrize("name", sorted(set(known_environments())))
def test_the_defaults_shown_are_the_ones_the_environment_runs_with(name: str) -> None:
    """Given every shown default explicitly, the world starts as it does without them."""
    doc = describe(name)
    given = {p.name: parse_parameter(p.default) for p in doc.parameters
             if p.default is not None}
    if name in SIMPLE or not given:
        assert _first_percepts(name, given) == sorted(doc.percepts)
    else:
        assert _first_percepts(name, given) == _first_percepts(name, {})


@pytest.mark.parametrize("name", sorted(set(known_environments()) - {"printer"}))
def test_the_hand_written_pages_name_every_percept_and_action(name: str) -> None:
    doc = describe(name)
    module = doc.path.split(":")[0]
    page = next((path for prefix, path in PAGES.items() if module.startswith(prefix)), None)
    if page is None:  # blocksworld, towerworld: goalagent/eis/README.md's table
        page = ROOT / "goalagent" / "eis" / "README.md"
    text = page.read_text()
    for indicator in _grouped(doc.percepts):
        assert f"`{indicator.split('/')[0]}" in text or f"{indicator.split('/')[0]}(" in text, (
            f"{page.name} does not mention the percept {indicator} of {name}")
    for action in doc.actions:
        assert action.name in text, f"{page.name} does not mention the action {action.name}"
