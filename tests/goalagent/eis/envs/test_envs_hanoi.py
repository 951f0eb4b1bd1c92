"""The hanoi environment: the Java model's percepts, moves and their refusals, and the
example solver reaching its goal from several starts."""

from __future__ import annotations

from pathlib import Path

import pytest

from goalagent.eis import ActionRefused, ManagementException, from_term
from goalagent.eis.envs.hanoi import Hanoi
from goalagent.eis.terms import Action
from goalagent.mas import MultiAgentSystem

EXAMPLES = Path(__file__).resolve().parents[4] / "agents" / "examples"


def running(discs: list[int] | None = None) -> Hanoi:
    env = Hanoi()
    env.init({} if discs is None else {"discs": from_term(discs)})
    env.start()
    env.register_agent("solver")
    env.associate_entity("solver", "entity")
    return env


def look(env: Hanoi) -> list[str]:
    return [str(p) for p in env.get_all_percepts("solver")["entity"]]


def test_percepts_every_cycle() -> None:
    env = running([0, 0, 1])
    assert env.entities() == ["entity"] and env.entity_type("entity") == "hanoicontroller"
    expected = ["disc(2,9)", "disc(1,10)", "disc(3,10)", "pins(3)",
                "on(2,0,1)", "on(1,0,0)", "on(3,1,0)"]
    assert look(env) == expected
    assert look(env) == expected  # all sent every cycle


def test_default_start_is_four_discs_on_pin_0() -> None:
    assert [p for p in look(running()) if p.startswith("on")] == [
        "on(4,0,3)", "on(3,0,2)", "on(2,0,1)", "on(1,0,0)"]


def test_moves() -> None:
    env = running([0, 0, 0])
    env.perform_action("solver", Action.of("move", 3, 2))
    env.perform_action("solver", Action.of("move", 2, 1))
    env.perform_action("solver", Action.of("move", 3, 1))
    assert [p for p in look(env) if p.startswith("on")] == ["on(1,0,0)", "on(3,1,2)", "on(2,1,0)"]


@pytest.mark.parametrize(
    ("disc", "pin", "reason"),
    [(1, 2, "disc 1 is under disc 3"), (3, 1, "larger than disc 4"), (7, 1, "no disc 7"),
     (3, 3, "no pin 3"), (4, 1, "is on pin 1 already")],
)
def test_refused_moves_change_nothing(disc: int, pin: int, reason: str) -> None:
    env = running([0, 0, 0, 1])
    before = look(env)
    with pytest.raises(ActionRefused, match=reason):
        env.perform_action("solver", Action.of("move", disc, pin))
    assert look(env) == before


@pytest.mark.parametrize(
    ("discs", "message"),
    [([0, 3], "each 0, 1 or 2"), ([], "1 to 9"), ("abc", "list of pin numbers")],
)
def test_bad_starts(discs: object, message: str) -> None:
    with pytest.raises(ManagementException, match=message):
        Hanoi().init({"discs": from_term(discs)})


@pytest.mark.parametrize(
    ("start", "moves"), [([0, 0, 0, 0], 15), ([2, 1, 0, 2, 1], None), ([2, 2, 2], 0)])
def test_the_example_solver_moves_every_disc_to_pin_2(start: list[int], moves: int) -> None:
    system = MultiAgentSystem.for_agent_file(EXAMPLES / "hanoi_solver.goal", environment="hanoi",
                                             env_params={"discs": start})
    try:
        (summary,) = system.run(max_cycles=100)
        assert summary.status == "terminated"
        pins = system.environment.pins
        assert pins[2] == sorted(pins[2]) and len(pins[2]) == len(start)
        if moves is not None:
            assert summary.cycles == moves + 1  # one move a cycle, then the goal is seen
    finally:
        system.close()


def test_snapshot(tmp_path: Path) -> None:
    env = running()
    env.snapshot(str(tmp_path / "h.png"))
    assert (tmp_path / "h.png").read_bytes()[:4] == b"\x89PNG"
