"""Blocks World for Teams (BW4T) as an EIS environment, with BW4T 3's percepts and actions.

Entities ``Bot_1`` ... (type ``bot``, ``agentcount`` of them) and ``Human_1`` ... (type
``human``, ``humancount``), named and typed as BW4T's server names them. Percepts, their
timing and actions follow BW4T's ``RobotEntity`` (see ``goalagent/eis/envs/README.md``);
``version`` chooses the vocabulary: BW4T 3.9+ (the default); 3.8.4 to 3.8.7, in which ``in``,
``atBlock``, ``holding``, ``player``, ``occupied`` and ``bumped`` are sent when they become
true and as ``not(...)`` when they stop being true; and before 3.8.4 (BW4T 2 too), where
moreover ``atBlock`` names only the closest block in reach and ``pickUp`` takes no argument.

Refused actions (``ActionRefused``) leave the world as it was; where BW4T would silently do
nothing (``pickUp`` of a block out of reach) the agent is told why instead.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from goalagent.eis.envs.bw4t.mapfile import colour_name, load_map
from goalagent.eis.envs.bw4t.render import draw_world
from goalagent.eis.envs.bw4t.robot import Robot, Unreachable
from goalagent.eis.envs.bw4t.world import World
from goalagent.eis.envs.filters import Filter, PerceptFilter
from goalagent.eis.envs.support import (
    RoundClock,
    SnapshotWriter,
    bool_param,
    check_known,
    int_param,
    text_param,
    write_png,
)
from goalagent.eis.exceptions import ActionRefused, ManagementException
from goalagent.eis.pyenv import PerceptLike, PythonEnvironment, action
from goalagent.eis.terms import Percept

ACCEPTED_AND_IGNORED = ("clientip", "clientport", "serverip", "serverport", "launchgui",
                        "agentclass", "goal", "kill", "configfile", "goalhuman", "log", "speed")
KNOWN_PARAMETERS = {
    "map": "map file path, or the name of a shipped map",
    "agentcount": "number of bot entities",
    "humancount": "number of human entities",
    "seed": "seed of the map's random parts when the map gives none",
    "ticks": "simulated ticks per round of agent cycles",
    "collision": "robots bump into each other",
    "version": "BW4T version whose vocabulary to use (3.10, 3.8.4, 3.8.0)",
    "snapshots": "directory for one PNG snapshot per round",
    **{key: "accepted and ignored (network, GUI, real-time speed)" for key in ACCEPTED_AND_IGNORED},
}
DEFAULT_MAP = "SixRooms"
NO_BLOCK = -1
NO_Y = float("nan")

# Percepts whose filter differs between BW4T 3.9+ (ALWAYS) and 3.8 / BW4T 2 (ON_CHANGE_NEG).
_NEGATED_IN_LEGACY = frozenset({"in", "atBlock", "holding", "player", "occupied", "bumped"})


def _version(version: str) -> tuple[int, ...]:
    """``3.8.5`` as (3, 8, 5); a missing part counts as 0."""
    parts = version.split(".")[:3]
    if not all(part.isdigit() for part in parts):
        raise ManagementException(f"bw4t: version must look like 3.10 or 3.8.5, got {version!r}")
    return tuple(int(part) for part in parts) + (0,) * (3 - len(parts))


class BW4T(PythonEnvironment):
    """Robots that find coloured blocks in rooms and deliver them to the drop zone in order."""

    name = "bw4t"
    default_version = "3.10"

    # ---- life cycle --------------------------------------------------------------------

    @classmethod
    def init_parameters(cls) -> dict[str, str]:
        return KNOWN_PARAMETERS

    @classmethod
    def init_key(cls, key: str) -> str:
        return key.lower()  # read in any case, as GOAL programs write them

    def on_init(self, params: dict[str, object]) -> None:
        """Load the map, spawn the robots, read the options."""
        params = {key.lower(): value for key, value in params.items()}
        check_known(self.name, params, KNOWN_PARAMETERS)
        self.map_name = text_param(self.name, params, "map", DEFAULT_MAP) or DEFAULT_MAP
        bots = int_param(self.name, params, "agentcount", 1, minimum=0)
        humans = int_param(self.name, params, "humancount", 0, minimum=0)
        seed = int_param(self.name, params, "seed", 0)
        self.ticks_per_round = int_param(self.name, params, "ticks", 4, minimum=1, maximum=1000)
        collision = bool_param(self.name, params, "collision", False)
        self.version = text_param(self.name, params, "version", self.default_version)
        version = _version(self.version)
        self.filter = PerceptFilter(legacy=version < (3, 9))
        self.closest_block_only = version < (3, 8, 4)
        self.world = World(load_map(self.map_name, self._map_folders()), seed, bots, humans,
                           collision)
        self.robots = {robot.name: robot for robot in self.world.robots}
        self.clock = RoundClock()
        self.inbox: dict[str, list[tuple[str, str]]] = {name: [] for name in self.robots}
        folder = params.get("snapshots")
        self.snapshots = None
        if folder is not None:
            folder = text_param(self.name, params, "snapshots", "")
            self.snapshots = SnapshotWriter(folder, "bw4t")

    def _map_folders(self) -> list[Path]:
        """Where a map named by a relative path is looked for before the shipped maps: the
        system's folder, then where BW4T 2's server, in ``BW4TServer`` beside the client jar
        the system names, keeps its maps (``maps/big12``)."""
        folders = [] if self.home is None else [self.home]
        if self.jar is not None:
            folders += [self.jar.parent / "BW4TServer" / "maps", self.jar.parent / "maps"]
        return folders

    def initial_entities(self) -> dict[str, str]:
        """One entity per robot, typed ``bot`` or ``human``."""
        return {name: robot.kind for name, robot in self.robots.items()}

    def advance(self, rounds: int = 1) -> None:
        """Run ``rounds`` rounds of simulated time (also done by agents' perceiving)."""
        for _ in range(rounds):
            for _ in range(self.ticks_per_round):
                self.world.tick()

    def snapshot(self, path: str) -> None:
        """Write a PNG of the world now to ``path`` (atomically)."""
        write_png(path, self.draw)

    def draw(self, figure: object) -> None:
        """Draw the world on a matplotlib figure."""
        draw_world(figure, self.world, self.clock.rounds)

    # ---- percepts ----------------------------------------------------------------------

    def percepts(self, entity: str) -> Iterable[PerceptLike]:
        """The percepts of ``entity`` this cycle, filtered as BW4T's EIS2Java filters them."""
        if self.clock.perceive(entity):
            self.advance()
            if self.snapshots is not None:
                self.snapshots.write(self.clock.rounds, self.draw)
        robot = self.robots[entity]
        result: list[Percept] = []
        for name, kind, produce in self._sources(robot):
            if kind is Filter.ONCE and self.filter.sent_once(entity, name):
                continue
            if name in _NEGATED_IN_LEGACY and self.filter.legacy:
                kind = Filter.ON_CHANGE_NEG
            result += self.filter.percepts(entity, name, kind, produce())
        robot.hold = False
        return result

    def _sources(self, robot: Robot) -> list[tuple[str, Filter, object]]:
        """(percept name, filter, producer of argument tuples) in BW4T's ``RobotEntity``."""
        world = self.world
        zone = robot.zone
        visible = world.blocks_in(zone.rect) if zone is not None else []
        room = world.room_at(robot.x, robot.y)
        at = world.nearest_zone(robot.x, robot.y)
        messages, self.inbox[robot.name] = self.inbox[robot.name], []
        f = Filter
        return [
            ("robotSize", f.ON_CHANGE,
             lambda: [(r.id, float(r.size), float(r.size)) for r in world.robots]),
            ("position", f.ON_CHANGE, lambda: self._positions(robot, zone, visible)),
            ("at", f.ON_CHANGE, lambda: [(at.name,)] if at is not None else []),
            ("atBlock", f.ALWAYS, lambda: self._at_blocks(robot)),
            ("in", f.ALWAYS, lambda: [(room.name,)] if room is not None else []),
            ("location", f.ON_CHANGE, lambda: [(robot.x, robot.y)]),
            ("place", f.ONCE, lambda: [(z.name,) for z in world.zones]),
            ("speed", f.ON_CHANGE, lambda: [(robot.speed_mod,)]),
            ("robot", f.ONCE, lambda: [(robot.id,)]),
            ("player", f.ALWAYS, lambda: [(p,) for p in self._players(robot.name)]),
            ("ownName", f.ONCE, lambda: [(robot.name,)]),
            ("color", f.ALWAYS, lambda: [(b.id, colour_name(b.colour)) for b in visible]),
            ("holding", f.ALWAYS, lambda: [(b.id,) for b in robot.holding]),
            ("holdingblocks", f.ON_CHANGE,
             lambda: [([b.id for b in reversed(robot.holding)],)]),
            ("gripperCapacity", f.ON_CHANGE, lambda: [(robot.capacity,)]),
            ("sequence", f.ONCE, lambda: [([colour_name(c) for c in world.sequence],)]),
            ("sequenceIndex", f.ON_CHANGE, lambda: [(world.sequence_index,)]),
            ("occupied", f.ALWAYS,
             lambda: [(z.name,) for z in world.zones if z.is_room and world.occupier(z)]),
            ("zone", f.ONCE, lambda: [(z.id, z.name, *z.centre, [n.name for n in z.neighbours])
                                      for z in world.zones]),
            ("message", f.ALWAYS, lambda: [([sender, text],) for sender, text in messages]),
            ("state", f.ON_CHANGE, lambda: [(robot.state,)]),
            ("battery", f.ON_CHANGE, lambda: [(100.0,)]),
            ("colorblind", f.ONCE, lambda: [(False,)]),
            ("bumped", f.ALWAYS,
             lambda: [(o.name,) for o in robot.obstacles] if robot.collided else []),
            ("oldTargetUnreachable", f.ON_CHANGE, lambda: [(robot.id, int(robot.unreachable))]),
        ]

    def _at_blocks(self, robot: Robot) -> list[tuple[int]]:
        """Blocks in reach; before BW4T 3.8.4 only the closest of them."""
        blocks = [b for b in self.world.blocks if robot.can_pick_up(b)]
        if self.closest_block_only and blocks:
            blocks = [min(blocks, key=lambda b: robot.distance_to(b.x, b.y))]
        return [(b.id,) for b in blocks]

    def _players(self, me: str) -> list[str]:
        """Entities of the agents that do not control ``me`` (``RobotEntity.getPlayers``)."""
        players: list[str] = []
        for agent in self.agents():
            entities = self.associated_entities(agent)
            if me not in entities:
                players += entities
        return players

    def _positions(self, robot: Robot, zone: object, visible: list) -> list[tuple]:
        """Only human entities get ``position`` percepts (BW4T's ``reportPositions``)."""
        if robot.kind != "human":
            return []
        world = self.world
        drop = world.drop_zone
        found = [(drop.id, *drop.centre)]
        found += [(z.id, *z.centre) for z in world.zones if z.is_room and z is not drop]
        found += [(b.id, b.x, b.y) for b in visible]
        if zone is not None:
            found += [(r.id, r.x, r.y) for r in world.robots
                      if r is not robot and zone.rect.contains(r.x, r.y)]
        found.append((robot.id, robot.x, robot.y))
        return found

    # ---- actions -----------------------------------------------------------------------

    def _visible_block(self, robot: Robot, block: int, what: str):
        zone = robot.zone
        for candidate in self.world.blocks_in(zone.rect) if zone is not None else []:
            if candidate.id == block:
                return candidate
        raise ActionRefused(f"{what}: there is no block with id {block} in sight of "
                            f"{robot.name} (blocks are seen only in the zone one is in)")

    @action("goTo")
    def go_to(self, entity: str, where: str | float, y: float = NO_Y) -> None:
        """``goTo(Place)``: to a zone's centre; ``goTo(X, Y)``: to a point."""
        robot = self.robots[entity]
        if isinstance(where, str):
            if y == y:  # a second argument after a place name
                raise ActionRefused(f"goTo({where},{y:g}): give a place name or two numbers")
            zone = self.world.by_name.get(where)
            if zone is None:
                raise ActionRefused(f"goTo({where}): there is no place {where} "
                                    f"(places: {', '.join(self.world.by_name)})")
            target, how = zone.centre, robot.go_to_object
        else:
            if y != y:
                raise ActionRefused(f"goTo({where:g}): give a place name or two numbers")
            target, how = (where, y), robot.go_to_point
        try:
            how(target)
        except Unreachable as error:
            raise ActionRefused(f"goTo: {error}") from None

    @action("goToBlock")
    def go_to_block(self, entity: str, block: int) -> None:
        """Go to a block seen in the zone one is in."""
        robot = self.robots[entity]
        found = self._visible_block(robot, block, f"goToBlock({block})")
        try:
            robot.go_to_object((found.x, found.y))
        except Unreachable as error:
            raise ActionRefused(f"goToBlock({block}): {error}") from None

    @action("pickUp")
    def pick_up(self, entity: str, block: int = NO_BLOCK) -> None:
        """``pickUp(Block)`` (BW4T 3.8.4+), or ``pickUp`` the nearest block in reach (older)."""
        robot = self.robots[entity]
        if len(robot.holding) >= robot.capacity:
            raise ActionRefused(f"pickUp: {robot.name} already holds {robot.capacity} "
                                f"block(s), its gripper capacity")
        if block == NO_BLOCK:
            reachable = [b for b in self.world.blocks if robot.can_pick_up(b)]
            if not reachable:
                raise ActionRefused(f"pickUp: no block within reach of {robot.name}")
            robot.pick_up(min(reachable, key=lambda b: robot.distance_to(b.x, b.y)))
            return
        found = self._visible_block(robot, block, f"pickUp({block})")
        if not robot.can_pick_up(found):
            distance = robot.distance_to(found.x, found.y)
            raise ActionRefused(f"pickUp({block}): the block is {distance:.1f} away, out of "
                                f"reach (goToBlock({block}) first)")
        robot.pick_up(found)

    @action("putDown")
    def put_down(self, entity: str) -> None:
        """Drop the top block held: delivered in the drop zone, else left in a room or lost."""
        robot = self.robots[entity]
        if not robot.holding:
            raise ActionRefused(f"putDown: {robot.name} holds no block")
        robot.drop()

    @action("navigateObstacles")
    def navigate_obstacles(self, entity: str) -> None:
        """After a collision: try the interrupted route again."""
        robot = self.robots[entity]
        if not robot.collided:
            raise ActionRefused(f"navigateObstacles: {robot.name} has not collided")
        if not robot.navigate_obstacles():
            raise ActionRefused(f"navigateObstacles: {robot.name} has no route to resume")

    @action("sendMessage")
    def send_message(self, entity: str, receiver: str, message: str) -> None:
        """Send ``message`` to entity ``receiver`` or to ``all`` (as ``message([From, Text])``)."""
        if receiver != "all" and receiver not in self.inbox:
            raise ActionRefused(f"sendMessage: there is no entity {receiver} "
                                f"(entities: {', '.join(self.inbox)}, or all)")
        for name in self.inbox if receiver == "all" else [receiver]:
            self.inbox[name].append((entity, message))

    @action("checkSequenceDone")
    def check_sequence_done(self, entity: str) -> None:
        """Accepted as in BW4T, where its answer is not a percept and so is never seen."""


class BW4T38(BW4T):
    """BW4T 3.8.4 to 3.8.7: negated percepts, ``pickUp(Block)``."""

    default_version = "3.8.4"


class BW4T2(BW4T):
    """BW4T 2 and BW4T 3 up to 3.8.3: negated percepts, ``atBlock`` of the closest block only,
    ``pickUp`` without argument."""

    default_version = "3.8.0"
