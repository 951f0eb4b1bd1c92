"""The blocksworld environment: percepts, move rules, init parameters, seeded random towers."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from goalagent.eis import (
    ActException,
    ActExceptionKind,
    Action,
    ActionRefused,
    ManagementException,
    Numeral,
    from_term,
    load_environment,
)
from goalagent.eis.envs.blocksworld import BlocksWorld
from goalagent.kb.terms import Atom, Struct


def on(x: str, y: str) -> Struct:
    return Struct("on", (Atom(x), Atom(y)))


def world(*state: Struct, **params: int) -> BlocksWorld:
    """A running blocksworld from ``state`` (or random towers) with agent ``ag`` on its
    gripper."""
    env = BlocksWorld()
    init = {key: Numeral(value) for key, value in params.items()}
    if state:
        init["state"] = from_term(list(state))
    env.init(init)
    env.start()
    env.register_agent("ag")
    env.associate_entity("ag", env.entities()[0])
    return env


def seen(env: BlocksWorld) -> list[str]:
    """The agent's percepts as Prolog text."""
    (percepts,) = env.get_all_percepts("ag").values()
    return [str(p) for p in percepts]


def move(env: BlocksWorld, x: str, y: str) -> None:
    env.perform_action("ag", Action.of("move", x, y))


def test_percepts_describe_the_state() -> None:
    env = world(on("a", "b"), on("b", "table"), on("c", "table"))
    assert seen(env) == [
        "block(a)", "block(b)", "block(c)", "on(a,b)", "on(b,table)", "on(c,table)"
    ]
    assert env.entities() == ["gripper"] and env.entity_type("gripper") == "gripper"


def test_moves_change_the_state() -> None:
    env = world(on("a", "b"), on("b", "table"), on("c", "table"))
    move(env, "a", "c")
    move(env, "b", "a")
    assert seen(env)[3:] == ["on(a,c)", "on(b,a)", "on(c,table)"]
    move(env, "b", "table")
    assert "on(b,table)" in seen(env)


@pytest.mark.parametrize(
    ("x", "y", "reason"),
    [
        ("b", "c", "b is not clear"),
        ("b", "table", "b is already on table"),
        ("c", "b", "b is not clear"),
        ("a", "a", "cannot be put on itself"),
        ("a", "b", "a is already on b"),
        ("z", "table", "z is not a block"),
        ("a", "z", "z is not a block"),
        ("table", "a", "table is not a block"),
    ],
)
def test_refused_moves_leave_the_world_unchanged(x: str, y: str, reason: str) -> None:
    env = world(on("a", "b"), on("b", "table"), on("c", "table"))
    before = seen(env)
    with pytest.raises(ActionRefused, match=reason):
        move(env, x, y)
    assert seen(env) == before


def test_wrong_action_forms_are_reported() -> None:
    env = world(on("a", "table"))
    with pytest.raises(ActException, match="move expects 2 parameters") as caught:
        env.perform_action("ag", Action.of("move", "a"))
    assert caught.value.kind is ActExceptionKind.WRONG_PARAMETERS
    with pytest.raises(ActException, match="no action 'pickup'") as caught:
        env.perform_action("ag", Action.of("pickup", "a"))
    assert caught.value.kind is ActExceptionKind.UNKNOWN_ACTION


@pytest.mark.parametrize(
    ("state", "message"),
    [
        ([on("a", "b"), on("b", "a")], "cycle"),
        ([on("a", "table"), on("a", "table")], "a is placed twice"),
        ([on("a", "b")], r"b is not placed; add on\(b, ...\)"),
        ([on("a", "c"), on("b", "c"), on("c", "table")], "both a and b are on c"),
        ([Struct("block", (Atom("a"),))], r"must be on\(Block, BlockOrTable\).*got block\(a\)"),
        ([on("table", "a"), on("a", "table")], "the table cannot be put on anything"),
    ],
)
def test_bad_states_are_clear_errors(state: list[Struct], message: str) -> None:
    with pytest.raises(ManagementException, match=message):
        BlocksWorld().init({"state": from_term(state)})


def test_other_bad_parameters() -> None:
    with pytest.raises(ManagementException, match="'state' must be a list"):
        BlocksWorld().init({"state": from_term(on("a", "table"))})
    with pytest.raises(ManagementException, match="blocks must be 0 to 10000, got -1"):
        BlocksWorld().init({"blocks": Numeral(-1)})
    with pytest.raises(ManagementException, match="blocks must be 0 to 10000"):
        BlocksWorld().init({"blocks": Numeral(10**9)})
    with pytest.raises(ManagementException, match=r"grippers \(robots\) must be at least 1"):
        BlocksWorld().init({"robots": Numeral(0)})


def test_random_towers_are_seeded() -> None:
    assert seen(world(seed=7)) == seen(world(seed=7))
    assert len({tuple(seen(world(seed=seed))) for seed in range(6)}) > 1
    assert seen(world(blocks=3, seed=1))[:3] == ["block(a)", "block(b)", "block(c)"]
    assert len(seen(world(blocks=30))) == 60
    assert seen(world(blocks=0)) == []


def test_several_robots_share_one_world() -> None:
    env = world(on("a", "table"), on("b", "table"), robots=2)
    assert env.entities() == ["gripper1", "gripper2"]
    env.register_agent("other")
    env.associate_entity("other", "gripper2")
    env.perform_action("other", Action.of("move", "a", "b"))
    assert "on(a,b)" in seen(env)


def test_registered_name_and_reset() -> None:
    env = load_environment("blocksworld")()
    env.init({"state": from_term([on("a", "table")])})
    env.reset({"state": from_term([on("x", "table")])})
    env.register_agent("ag")
    env.associate_entity("ag", "gripper")
    assert [str(p) for p in env.get_all_percepts("ag")["gripper"]] == [
        "block(x)", "on(x,table)"]


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 10_000),
    moves=st.lists(st.tuples(st.integers(0, 5), st.integers(0, 5)), max_size=25),
)
def test_any_move_sequence_keeps_a_valid_world(seed: int, moves: list[tuple[int, int]]) -> None:
    env = world(seed=seed, blocks=5)
    names = ["a", "b", "c", "d", "e", "table"]
    for x, y in moves:
        before = dict(env.on)
        try:
            move(env, names[x], names[y])
        except ActionRefused:
            assert env.on == before
            continue
        assert env.on[names[x]] == names[y]
    below = [y for y in env.on.values() if y != "table"]
    assert len(below) == len(set(below))  # at most one block on each block
    for block in env.on:  # every block rests on the table through a finite chain
        chain = block
        for _ in range(len(env.on)):
            chain = env.on.get(chain, chain)
        assert chain == "table"


# ----------------------------------------------------------------------------- GOAL's vocabulary


def goal_world(start: object, home=None, **extra: object) -> BlocksWorld:
    """A blocksworld from GOAL's ``start`` parameter (a list of numbers or a file name)."""
    env = BlocksWorld()
    env.home = home
    env.init({"start": from_term(start), **{k: from_term(v) for k, v in extra.items()}})
    env.start()
    env.register_agent("ag")
    env.associate_entity("ag", "gripper")
    return env


def test_the_guides_start_state_names_blocks_b1_to_bn() -> None:
    env = goal_world([2, 3, 0, 5, 0, 7, 0], gui=Atom("true"))
    assert [p for p in seen(env) if p.startswith("on(")] == [
        "on(b1,b2)", "on(b2,b3)", "on(b3,table)", "on(b4,b5)", "on(b5,table)",
        "on(b6,b7)", "on(b7,table)"]
    env.perform_action("ag", Action.of("move", "b1", "table"))
    assert "on(b1,table)" in seen(env)


def test_a_start_file_is_read_next_to_the_system_first(tmp_path, monkeypatch) -> None:
    (tmp_path / "config.txt").write_text("0 1\n4 0\n")
    monkeypatch.chdir("/")
    env = goal_world("config.txt", home=tmp_path)
    assert [p for p in seen(env) if p.startswith("on(")] == [
        "on(b1,table)", "on(b2,b1)", "on(b3,b4)", "on(b4,table)"]
    with pytest.raises(ManagementException, match="no start file missing.txt"):
        goal_world("missing.txt", home=tmp_path)


@pytest.mark.parametrize("start, message", [
    ([2, 1], "cycle"),
    ([0, 1, 1], "both b2 and b3 are on b1"),
    ([4, 0], "start numbers must be 0 .* to 2"),
    ([1], "puts b1 on itself"),
])
def test_bad_start_numbers_are_refused(start: list[int], message: str) -> None:
    with pytest.raises(ManagementException, match=message):
        goal_world(start)


def test_start_and_state_together_are_refused() -> None:
    with pytest.raises(ManagementException, match="give start or state, not both"):
        goal_world([0], state=[on("a", "table")])
