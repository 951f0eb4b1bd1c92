"""The bw4t environment: maps, entities, each percept's timing, actions and their refusals,
occupied rooms, deliveries, the 3.8 vocabulary, snapshots, and a team reaching its goal."""

from __future__ import annotations

from pathlib import Path

import pytest

from goalagent.eis import ActException, Action, ActionRefused, ManagementException
from goalagent.eis.envs.bw4t.environment import BW4T, BW4T2, BW4T38
from goalagent.eis.envs.bw4t.mapfile import load_map, parse_map, shipped_maps
from goalagent.eis.envs.bw4t.world import World
from goalagent.mas import MultiAgentSystem

EXAMPLES = Path(__file__).resolve().parents[4] / "agents" / "examples"


def running(cls: type[BW4T] = BW4T, **params: object) -> BW4T:
    """A started environment with agent ``a1`` on Bot_1, ``a2`` on Bot_2, ..."""
    env = cls()
    env.init({"map": "TwoRooms", **params})
    env.start()
    for index, entity in enumerate(env.entities(), 1):
        env.register_agent(f"a{index}")
        env.associate_entity(f"a{index}", entity)
    return env


def look(env: BW4T, agent: str = "a1") -> list[str]:
    """One perceive call of ``agent`` (one agent cycle), as Prolog text."""
    (percepts,) = env.get_all_percepts(agent).values()
    return [str(p) for p in percepts]


def named(seen: list[str], *names: str) -> list[str]:
    return [p for p in seen if p.split("(")[0] in names]


def act(env: BW4T, name: str, *args: object, agent: str = "a1") -> None:
    env.perform_action(agent, Action.of(name, *args))


def until(env: BW4T, percept: str, limit: int = 200, agent: str = "a1") -> list[list[str]]:
    """Cycles of ``agent`` until ``percept`` is seen; every cycle's percepts."""
    cycles = []
    for _ in range(limit):
        cycles.append(look(env, agent))
        if percept in cycles[-1]:
            return cycles
    raise AssertionError(f"{percept} not seen in {limit} cycles")


# ---- maps ---------------------------------------------------------------------------------


def test_shipped_maps_load() -> None:
    assert shipped_maps() == ["Banana", "Corridor", "Dutch Flag", "Rainbow", "Random", "SixRooms",
                             "SuperRandom", "TwoRooms"]
    for name in shipped_maps():
        world = World(load_map(name), seed=0, bots=3)
        assert world.drop_zone.name == "DropZone" and world.sequence
        assert all(world.find_path(world.robots[0].zone, z) for z in world.zones)


MAPS = Path(__file__).resolve().parents[4] / "goalagent" / "eis" / "envs" / "bw4t" / "maps"


def test_map_by_path(tmp_path: Path) -> None:
    copy = tmp_path / "mine.map"
    copy.write_text((MAPS / "TwoRooms.map").read_text())
    assert load_map(str(copy)).name == "mine"
    assert load_map("TwoRooms.map").name == "TwoRooms"


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (("newMap>", "map>"), "root element must be <newMap>"),
        (("</newMap>", ""), "not readable XML at line"),
        (("<name>DropZone</name>", "<name>Drop</name>"), "neighbour 'DropZone' is not a zone"),
        (("<blocks>RED</blocks>", "<blocks>MAUVE</blocks>"), "unknown colour 'MAUVE'"),
        (("<type>CORRIDOR</type>", "<type>HALL</type>"), "unknown type 'HALL'"),
        (("<width>10.0</width>", "<width>ten</width>"), "<width> must be a number"),
        (("<sequence>RED</sequence>", "<sequence>TEAL</sequence>"), "unknown colour 'TEAL'"),
        (("<name>MidHall</name>", "<name>LeftHall</name>"), "two zones are called 'LeftHall'"),
    ],
)
def test_bad_maps_are_clear_errors(change: tuple[str, str], message: str) -> None:
    text = (MAPS / "TwoRooms.map").read_text()
    with pytest.raises(ManagementException, match=message):
        parse_map(text.replace(*change, 1 if change[0] != "newMap>" else -1), "bad")


def test_seeded_random_maps_repeat_and_differ_by_seed() -> None:
    spec = load_map("Corridor")  # random blocks and sequence, seed 11 in the file
    one, two = World(spec, seed=5, bots=1), World(spec, seed=99, bots=1)
    assert [(b.colour, b.x, b.y) for b in one.blocks] == [(b.colour, b.x, b.y) for b in two.blocks]
    assert len(one.sequence) == 3 and len(one.blocks) == 9
    unseeded = parse_map(
        (MAPS / "Corridor.map").read_text().replace("<seed>11</seed>", ""), "x")
    a, b = World(unseeded, seed=1, bots=1), World(unseeded, seed=2, bots=1)
    assert [(x.colour, x.x) for x in a.blocks] != [(x.colour, x.x) for x in b.blocks]


# ---- entities and init parameters ------------------------------------------------------------


def test_entities_are_bw4t_bots_and_humans() -> None:
    env = running(agentcount="2", humancount=1)
    assert env.entities() == ["Bot_1", "Bot_2", "Human_1"]
    assert [env.entity_type(e) for e in env.entities()] == ["bot", "bot", "human"]


def test_real_init_parameters_are_accepted() -> None:
    env = BW4T()
    env.init({"map": "TwoRooms", "clientip": "localhost", "clientport": "2000",
              "serverip": "localhost", "serverport": "8000", "agentcount": "3",
              "humancount": "0", "launchgui": "false", "goal": "true", "Speed": "0.5"})
    assert len(env.entities()) == 3


@pytest.mark.parametrize(
    ("params", "message"),
    [
        ({"colour": 1}, "no init parameter 'colour'"),
        ({"agentcount": "four"}, "'agentcount' must be a whole number"),
        ({"agentcount": 4}, "3 robot start positions, 4 robots asked for"),
        ({"map": "Nowhere"}, "no map file 'Nowhere'.*shipped: Banana, Corridor, .*TwoRooms"),
        ({"version": "new"}, "version must look like 3.10"),
        ({"ticks": 0}, "'ticks' must be in 1..1000"),
    ],
)
def test_bad_init_parameters(params: dict, message: str) -> None:
    with pytest.raises(ManagementException, match=message):
        BW4T().init({"map": "TwoRooms", **params})


# ---- percept timing --------------------------------------------------------------------------


def test_once_percepts_come_in_the_first_cycle_only() -> None:
    env = running()
    first, second = look(env), look(env)
    for name in ("zone", "place", "sequence", "robot", "ownName", "colorblind"):
        assert named(first, name), name
        assert not named(second, name), name
    assert "zone(3,'RoomA',5.0,5.0,['LeftHall'])" in first
    assert "sequence(['Red','Blue'])" in first and "ownName('Bot_1')" in first


def test_on_change_percepts_come_when_they_change() -> None:
    env = running()
    first = look(env)
    for name in ("state", "at", "sequenceIndex", "location", "holdingblocks",
                 "gripperCapacity", "speed", "battery", "robotSize", "oldTargetUnreachable"):
        assert named(first, name), name
    assert not named(look(env), "state", "at", "sequenceIndex", "location", "holdingblocks")
    assert "state(arrived)" in first and "at('MidHall')" in first


def test_traveling_is_seen_before_arrived() -> None:
    env = running()
    look(env)
    act(env, "goTo", "RoomA")
    cycles = until(env, "state(arrived)")
    assert named(cycles[0], "state") == ["state(traveling)"]  # the first cycle after goTo
    states = [s for c in cycles for s in named(c, "state")]
    assert states == ["state(traveling)", "state(arrived)"]
    ats = [a for c in cycles for a in named(c, "at")]
    assert ats == ["at('LeftHall')", "at('RoomA')"]  # via the corridor, each once
    assert len(cycles) > 5  # moving takes time


def test_room_percepts_are_sent_every_cycle_while_true() -> None:
    env = running()
    look(env)
    act(env, "goTo", "RoomA")
    cycles = until(env, "state(arrived)")
    inside = [c for c in cycles if "in('RoomA')" in c]
    assert inside and all("color(12,'Red')" in c and "color(13,'Blue')" in c for c in inside)
    later = look(env)
    assert "in('RoomA')" in later and "color(12,'Red')" in later and "occupied('RoomA')" in later
    assert named(later, "atBlock")  # a block within reach at the room's centre


def test_player_percept_lists_the_other_agents_entities() -> None:
    env = running(agentcount=3)
    assert named(look(env, "a2"), "player") == ["player('Bot_1')", "player('Bot_3')"]
    assert named(look(env, "a2"), "player") == ["player('Bot_1')", "player('Bot_3')"]


def test_legacy_versions_negate_percepts_that_stop() -> None:
    env = running(BW4T38)
    look(env)
    act(env, "goTo", "RoomA")
    until(env, "in('RoomA')")
    assert "in('RoomA')" not in look(env)  # sent once, on becoming true
    act(env, "goTo", "LeftHall")
    cycles = until(env, "not(in('RoomA'))")
    assert "not(in('RoomA'))" in cycles[-1]
    assert not named(look(env), "not")
    assert running(version="3.9").filter.legacy is False
    assert running(version="2").filter.legacy is True


def test_before_3_8_4_at_block_names_the_closest_block_only() -> None:
    def in_reach(env: BW4T) -> set[str]:
        """The atBlock facts true at the end, kept up to date from the (negated) percepts."""
        look(env)
        act(env, "goTo", 5.0, 3.0)  # in RoomA, within reach of the red and the blue block
        true: set[str] = set()
        for cycle in until(env, "state(arrived)") + [look(env)]:
            for percept in named(cycle, "atBlock", "not"):
                if percept.startswith("not(atBlock("):
                    true.discard(percept[4:-1])
                elif percept.startswith("atBlock("):
                    true.add(percept)
        return true

    assert in_reach(running(BW4T38)) == {"atBlock(12)", "atBlock(13)"}
    assert len(in_reach(running(BW4T2))) == 1


# ---- actions -------------------------------------------------------------------------------


def fetch(env: BW4T, room: str, block: int) -> None:
    """Walk Bot_1 to ``room``, to ``block``, and pick it up."""
    act(env, "goTo", room)
    until(env, "state(arrived)")
    act(env, "goToBlock", block)
    until(env, "state(arrived)")
    act(env, "pickUp", block)


def test_deliveries_follow_the_sequence() -> None:
    env = running()
    look(env)
    fetch(env, "RoomA", 13)  # blue: not the next colour (red is)
    assert "holding(13)" in look(env)
    act(env, "goTo", "DropZone")
    until(env, "state(arrived)")
    act(env, "putDown")
    seen = look(env)
    assert not named(seen, "sequenceIndex", "holding")  # the blue block is lost
    assert 13 not in [b.id for b in env.world.blocks if b.placed]
    fetch(env, "RoomA", 12)  # red
    act(env, "goTo", "DropZone")
    until(env, "state(arrived)")
    act(env, "putDown")
    assert "sequenceIndex(1)" in look(env)
    assert env.world.sequence_index == 1


def test_blocks_put_down_in_a_room_stay_there() -> None:
    env = running()
    look(env)
    fetch(env, "RoomA", 12)
    act(env, "putDown")
    block = next(b for b in env.world.blocks if b.id == 12)
    assert block.placed and env.world.by_name["RoomA"].rect.contains(block.x, block.y)
    assert "color(12,'Red')" in look(env)


def test_an_occupied_room_stops_a_second_robot_at_the_door() -> None:
    env = running(agentcount=2)
    look(env, "a1"), look(env, "a2")
    act(env, "goTo", "RoomA", agent="a1")
    act(env, "goTo", "RoomA", agent="a2")
    stopped = None
    for _ in range(150):
        seen = {agent: look(env, agent) for agent in ("a1", "a2")}
        stopped = next((a for a in seen if "state(collided)" in seen[a]), None)
        if stopped:
            break
    assert stopped is not None, "neither robot was stopped at the door"
    inside = "a1" if stopped == "a2" else "a2"
    robot = env.robots[env.associated_entities(stopped)[0]]
    assert env.world.door_at(robot.x, robot.y) is not None  # stopped in the doorway
    assert "occupied('RoomA')" in seen[stopped] and "in('RoomA')" not in seen[stopped]
    assert "in('RoomA')" in look(env, inside)
    act(env, "goTo", "MidHall", agent=inside)  # the first one leaves, the other gets in
    until(env, "state(arrived)", agent=inside)
    act(env, "goTo", "RoomA", agent=stopped)
    until(env, "in('RoomA')", agent=stopped)


def test_messages_between_robots() -> None:
    env = running(agentcount=2)
    act(env, "sendMessage", "Bot_2", "hello", agent="a1")
    act(env, "sendMessage", "all", "hi", agent="a2")
    assert named(look(env, "a2"), "message") == [
        "message(['Bot_1',hello])", "message(['Bot_2',hi])"]
    assert named(look(env, "a1"), "message") == ["message(['Bot_2',hi])"]
    assert not named(look(env, "a1"), "message")


def world_state(env: BW4T) -> tuple:
    w = env.world
    return (w.sequence_index, [(b.id, b.x, b.y, b.placed, b.holder is not None) for b in w.blocks],
            [(r.x, r.y, r.state, len(r.holding), tuple(r.planned)) for r in w.robots])


@pytest.mark.parametrize(
    ("action", "reason"),
    [
        (("goTo", "Kitchen"), "there is no place Kitchen"),
        (("goTo", 5), "give a place name or two numbers"),
        (("goTo", "RoomA", 3), "give a place name or two numbers"),
        (("goToBlock", 12), "no block with id 12 in sight"),
        (("pickUp", 12), "no block with id 12 in sight"),
        (("pickUp",), "no block within reach"),
        (("putDown",), "holds no block"),
        (("navigateObstacles",), "has not collided"),
        (("sendMessage", "Bot_9", "x"), "there is no entity Bot_9"),
    ],
)
def test_refused_actions_leave_the_world_unchanged(action: tuple, reason: str) -> None:
    env = running()
    look(env)
    before = world_state(env)
    with pytest.raises(ActionRefused, match=reason):
        act(env, *action)
    assert world_state(env) == before


def test_pick_up_refusals_in_a_room() -> None:
    env = running()
    look(env)
    act(env, "goTo", "RoomA")
    until(env, "state(arrived)")
    far = max(env.world.blocks_in(env.world.by_name["RoomA"].rect),
              key=lambda b: env.robots["Bot_1"].distance_to(b.x, b.y))
    before = world_state(env)
    if env.robots["Bot_1"].distance_to(far.x, far.y) > 3:
        with pytest.raises(ActionRefused, match="out of reach"):
            act(env, "pickUp", far.id)
        assert world_state(env) == before
    act(env, "goToBlock", 12)
    until(env, "state(arrived)")
    act(env, "pickUp", 12)
    with pytest.raises(ActionRefused, match="gripper capacity"):
        act(env, "pickUp", 13)


def test_wrong_parameters_are_act_exceptions() -> None:
    env = running()
    with pytest.raises(ActException, match="expects"):
        act(env, "putDown", 1)
    with pytest.raises(ActException, match="has no action 'fly'"):
        act(env, "fly")


def test_go_to_a_point_and_old_pick_up() -> None:
    env = running()
    look(env)
    act(env, "goTo", 5.0, 4.0)  # inside RoomA, near block 12 (red)
    until(env, "state(arrived)")
    assert (env.robots["Bot_1"].x, env.robots["Bot_1"].y) == pytest.approx((5.0, 4.0))
    act(env, "pickUp")  # BW4T 3.8: the nearest block in reach
    assert len(env.robots["Bot_1"].holding) == 1


def test_with_collisions_robots_bump_into_each_other() -> None:
    env = running(agentcount=2, collision="true")
    look(env, "a1"), look(env, "a2")
    act(env, "goTo", "LeftHall", agent="a2")  # Bot_2 crosses Bot_1's way to MidHall's centre
    act(env, "goTo", "RightHall", agent="a1")
    bumped = None
    for _ in range(60):
        seen = {agent: look(env, agent) for agent in ("a1", "a2")}
        bumped = next((a for a in seen if named(seen[a], "bumped")), None)
        if bumped:
            break
    assert bumped is not None, "no robot bumped into the other"
    assert "state(collided)" in seen[bumped]
    other = "Bot_1" if bumped == "a2" else "Bot_2"
    assert named(seen[bumped], "bumped") == [f"bumped('{other}')"]
    act(env, "navigateObstacles", agent=bumped)  # try again
    assert env.robots[env.associated_entities(bumped)[0]].state == "traveling"
    assert not running(agentcount=2).world.collision  # off by default, as BW4T's server


def test_only_human_entities_get_positions() -> None:
    env = running(agentcount=1, humancount=1)
    human, bot = look(env, "a2"), look(env, "a1")
    assert not named(bot, "position")
    positions = named(human, "position")
    drop = env.world.drop_zone
    assert positions[0] == f"position({drop.id},{drop.centre[0]},{drop.centre[1]})"
    robot = env.robots["Human_1"]
    assert positions[-1] == f"position({robot.id},{robot.x},{robot.y})"
    bot1 = env.robots["Bot_1"]  # in the same zone, so visible
    assert positions[1:-1] == ["position(3,5.0,5.0)", "position(5,25.0,5.0)",
                               f"position({bot1.id},{bot1.x},{bot1.y})"]


# ---- snapshots and a whole team ---------------------------------------------------------------


def test_snapshots_one_png_per_round(tmp_path: Path) -> None:
    env = running(snapshots=str(tmp_path), agentcount=2)
    for _ in range(3):
        look(env, "a1"), look(env, "a2")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bw4t-000001.png", "bw4t-000002.png"]
    env.snapshot(str(tmp_path / "now.png"))
    assert (tmp_path / "now.png").read_bytes()[:4] == b"\x89PNG"


def test_the_example_team_delivers_the_sequence() -> None:
    system = MultiAgentSystem.from_mas_file(EXAMPLES / "bw4t_team.mas2g")
    try:
        summaries = system.run(max_cycles=600)
        world = system.environment.world
        assert world.sequence_done and len(world.sequence) == 6
        assert [s.status for s in summaries] == ["terminated"] * 3
    finally:
        system.close()


def test_the_example_robot_alone() -> None:
    system = MultiAgentSystem.for_agent_file(EXAMPLES / "bw4t_robot.goal", environment="bw4t",
                                             env_params={"map": "TwoRooms"}, seed=0)
    try:
        (summary,) = system.run(max_cycles=600)
        assert summary.status == "terminated" and system.environment.world.sequence_done
    finally:
        system.close()
