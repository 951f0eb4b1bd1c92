"""The towerworld environment: the gripper's pickup/putdown/nil rules and its percepts."""

from __future__ import annotations

import pytest

from goalagent.eis import Action, ActionRefused, Numeral, from_term
from goalagent.eis.envs.towerworld import TowerWorld
from goalagent.kb.terms import Atom, Struct


def tower(*pairs: tuple[str, str]) -> TowerWorld:
    """A running tower world with agent ``ag`` on the gripper."""
    env = TowerWorld()
    env.init({"state": from_term([Struct("on", (Atom(x), Atom(y))) for x, y in pairs])})
    env.start()
    env.register_agent("ag")
    env.associate_entity("ag", "gripper")
    return env


def seen(env: TowerWorld) -> list[str]:
    return [str(p) for p in env.get_all_percepts("ag")["gripper"]]


def do(env: TowerWorld, name: str, *args: str) -> None:
    env.perform_action("ag", Action.of(name, *args))


def test_pickup_and_putdown() -> None:
    env = tower(("a", "b"), ("b", "table"), ("c", "table"))
    assert env.entities() == ["gripper"] and env.entity_type("gripper") == "gripper"
    do(env, "pickup", "a")
    assert seen(env) == ["block(a)", "block(b)", "block(c)", "on(b,table)", "on(c,table)",
                         "holding(a)"]
    do(env, "putdown", "a", "c")
    assert seen(env) == ["block(a)", "block(b)", "block(c)", "on(a,c)", "on(b,table)",
                         "on(c,table)"]
    do(env, "pickup", "b")
    do(env, "putdown", "b", "table")
    do(env, "nil")
    assert "on(b,table)" in seen(env)


@pytest.mark.parametrize(
    ("steps", "action", "reason"),
    [
        ([], ("pickup", "b"), "b is not clear"),
        ([], ("pickup", "z"), "z is not a block"),
        ([("pickup", "a")], ("pickup", "c"), "already holds a"),
        ([], ("putdown", "a", "table"), "holds nothing, not a"),
        ([("pickup", "a")], ("putdown", "c", "table"), "holds a, not c"),
        ([("pickup", "c")], ("putdown", "c", "b"), "b is not clear"),
        ([("pickup", "a")], ("putdown", "a", "a"), "cannot be put on itself"),
        ([("pickup", "a")], ("putdown", "a", "z"), "z is not a block"),
    ],
)
def test_refused_actions_leave_the_world_unchanged(
    steps: list[tuple[str, ...]], action: tuple[str, ...], reason: str
) -> None:
    env = tower(("a", "b"), ("b", "table"), ("c", "table"))
    for step in steps:
        do(env, *step)
    before = seen(env)
    with pytest.raises(ActionRefused, match=reason):
        do(env, *action)
    assert seen(env) == before


def test_random_start_is_seeded_and_gripper_empty() -> None:
    def start(seed: int) -> list[str]:
        env = TowerWorld()
        env.init({"seed": Numeral(seed), "blocks": Numeral(4)})
        env.register_agent("ag")
        env.associate_entity("ag", "gripper")
        return [str(p) for p in env.get_all_percepts("ag")["gripper"]]

    assert start(3) == start(3)
    assert not any(p.startswith("holding") for p in start(3))
    assert len(start(3)) == 8
